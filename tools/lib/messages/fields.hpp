// Field paths of our LCM messages, shared by state-logger, log2csv and plotter:
// decode a payload by its fingerprint and flatten its numbers and strings to
// (path, value) pairs such as `utime`, `position[0]`, `data[2]`, `message` (the CSV columns), each with the label
// the dashboard shows (`position[j1]`); a field is asked for by either (select_fields).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace lcm_control::tools {

// One number or string of a message. Integers keep their exact value (utime, request ids).
struct Field {
  std::string path;
  double value = 0;  // 0 for a string
  int64_t exact = 0;
  bool integer = false;
  bool is_text = false;  // a string field: its value is `str`, not a number to plot
  std::string str;
  std::string label;  // the dashboard's name: rows named by the string array the schema gives (position[j1]); "" = path
  std::string text() const;
  const std::string& name() const { return label.empty() ? path : label; }  // exact integers, shortest round-trip doubles, strings as they are (unquoted)
};

struct Decoded {
  std::string type;         // "lcm_control.joint_state_t", "" if the fingerprint is not one of ours
  std::string skip_reason;  // why this payload has no fields ("" when fields were decoded)
  std::vector<Field> fields;
  bool ok() const { return skip_reason.empty(); }
};

// Decodes one LCM payload by the fingerprint in its first 8 bytes. Array-length
// fields are left out; booleans are 0/1. Strings come after all the numbers, so
// a numeric column has the same position as in a file without strings.
Decoded decode_fields(const void* data, size_t size);

// The fields `wanted` names: the one whose path or label it is (`position[1]`, `position[j2]`), else all under it
// (`position` -> position[0], position[1], ...); none when it names none. A leading '.' or '/' is ignored.
std::vector<const Field*> select_fields(const std::vector<Field>& fields, const std::string& wanted);

// Up to `most` numeric field names (labels, paths, and what holds them: position) nearest to `wanted`, nearest first:
// what an unknown field's error suggests.
std::vector<std::string> nearest_fields(const std::vector<Field>& fields, const std::string& wanted, size_t most = 5);

// The unit the schema gives a field path of a message type ("lcm_control.joint_state_t", "position[1]" ->
// "rad or m"; "link_poses_t", "position[rotor].z" -> "m"); "" when it gives none.
std::string field_unit(const std::string& type, const std::string& path);

// Every type decode_fields knows: "name" or "name (skipped: reason)", for --help texts.
std::vector<std::string> known_types();

// "j2_controller/command" -> "j2_controller__command.csv": one CSV per channel.
std::string csv_file_name(const std::string& channel);

}  // namespace lcm_control::tools
