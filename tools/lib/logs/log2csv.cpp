#include "tools/lib/logs/log2csv.hpp"

#include <filesystem>
#include <map>
#include <memory>
#include <regex>
#include <set>

#include "description/text.hpp"
#include "tools/lib/messages/csv.hpp"
#include "tools/lib/messages/fields.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/logs/log_file.hpp"

namespace lcm_control::tools {

void add_log2csv_flags(CLI::App& app, Log2CsvFlags& f) {
  app.add_option("LOGFILE", f.log_path, "log file written by lcm-logger")->required();
  app.add_option("--output-dir", f.output_dir, "folder for the CSV files (created if needed)");
  app.add_option("-c,--channel", f.channel_regex, "only channels that this regular expression matches in full");
  app.add_option("--field", f.wanted,
                 "only these columns (and utime): field paths (position[1], or position for all its elements) or the "
                 "dashboard's labels (position[j2]); repeatable");
  app.add_flag("--log-time", f.log_time, "add a first column log_utime: when lcm-logger received the message");
}

int run_log2csv(const Log2CsvFlags& f) {
  std::regex filter;
  try {
    // ROS's /joint_states too: a channel never starts with '/'.
    const std::string pattern = without_leading_slashes(f.channel_regex);
    filter = std::regex(pattern.empty() ? ".*" : pattern, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw std::runtime_error(fmt::format("--channel '{}' is not a valid regular expression: {}", f.channel_regex,
                                         e.what()));
  }
  const auto log_file = open_log(f.log_path);
  lcm::LogFile& log = *log_file;
  std::error_code ec;
  std::filesystem::create_directories(f.output_dir, ec);
  if (ec) throw std::runtime_error("cannot create " + f.output_dir + ": " + ec.message());

  // Keeps the columns --field names (utime first); notes which --field found a column, and the nearest names of
  // the first channel that lacked one.
  std::set<std::string> found;
  std::map<std::string, std::string> nearest;  // field -> "joint_states: position[j1], ..."
  auto keep_wanted = [&](Decoded& d, const std::string& channel) {
    if (f.wanted.empty()) return;
    std::vector<Field> kept;
    for (const auto& f : d.fields)
      if (f.path == "utime") kept.push_back(f);
    for (const auto& w : f.wanted) {
      const std::vector<const Field*> picked = select_fields(d.fields, w);
      for (const Field* f : picked)
        if (f->path != "utime") kept.push_back(*f);
      if (!picked.empty())
        found.insert(w);
      else if (const auto near = nearest_fields(d.fields, w); !nearest.count(w) && !near.empty())
        nearest[w] = fmt::format("{}: {}", channel, join(near));
    }
    d.fields = std::move(kept);
  };
  struct Channel {
    std::string type, skip_reason;
    std::unique_ptr<CsvWriter> csv;
    size_t other = 0;
  };
  std::map<std::string, Channel> seen;
  size_t events = 0, filtered = 0;
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent()) {
    ++events;
    if (!std::regex_match(ev->channel, filter)) {
      ++filtered;
      continue;
    }
    Channel& c = seen[ev->channel];
    if (!c.skip_reason.empty()) continue;
    Decoded d = decode_fields(ev->data, size_t(ev->datalen));
    if (d.ok()) keep_wanted(d, ev->channel);
    if (!c.csv) {
      if (ev->channel == "LCM_SELF_TEST") d.skip_reason = "LCM's own self-test traffic, not a message";
      if (d.ok() && !f.wanted.empty() && d.fields.size() <= 1) d.skip_reason = "none of the --field columns";
      if (!d.ok()) {
        c.type = d.type;
        c.skip_reason = d.skip_reason;
        continue;
      }
      c.type = d.type;
      c.csv = std::make_unique<CsvWriter>(
          (std::filesystem::path(f.output_dir) / csv_file_name(ev->channel)).string());
    }
    if (!d.ok() || d.type != c.type) {
      ++c.other;
      continue;
    }
    if (f.log_time)
      d.fields.insert(d.fields.begin(), Field{"log_utime", double(ev->timestamp), ev->timestamp, true, false, "", ""});
    c.csv->write(d.fields);
  }
  std::string unknown;
  for (const auto& w : f.wanted)
    if (!found.count(w))
      unknown += fmt::format("\n  --field {}: {}", w,
                             nearest.count(w) ? "nearest in " + nearest[w] : "no near name in the channels read");
  if (!unknown.empty())
    throw std::runtime_error(fmt::format("{}: no column of these names in any channel read:{}", f.log_path, unknown));
  size_t written = 0;
  for (auto& [name, c] : seen) {
    if (c.csv) {
      c.csv->flush();
      ++written;
      fmt::print("wrote {}: {} rows, {} columns ({}, channel {}){}\n", c.csv->path(), c.csv->rows(),
                 c.csv->columns(), c.type, name,
                 c.other ? fmt::format("; {} messages of another type left out", c.other) : "");
    }
  }
  for (auto& [name, c] : seen)
    if (!c.csv)
      fmt::print("skipped {}: {}{}\n", name, c.type.empty() ? "" : c.type + ": ", c.skip_reason);
  if (filtered) fmt::print("{} of {} messages were on channels --channel does not match\n", filtered, events);
  if (written == 0)
    throw std::runtime_error(fmt::format("{}: no channel of lcm_control types{} ({} messages read)", f.log_path,
                                         f.channel_regex.empty() ? "" : " matching --channel", events));
  return int(kExitOk);
}

}  // namespace lcm_control::tools
