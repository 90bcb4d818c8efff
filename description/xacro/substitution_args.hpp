// xacro's `$(...)` substitution args: arg, find, env, optenv, eval, dirname, cwd, anon (the rules of xacro's
// substitution_args.py, with $(dirname) the folder of the file being read and $(anon) as ROS 1 had it).
#pragma once

#include <functional>
#include <map>
#include <string>

namespace lcm_control::xacro {

struct SubstitutionContext {
  const std::map<std::string, std::string>* args = nullptr;  // xacro's args: the command line's, then xacro:arg's
  std::function<std::string(const std::string&)> find_package;  // "" when absent
  std::string package_search_note;
  std::string current_file;                          // the file being read, for $(dirname)
  std::map<std::string, std::string>* anon = nullptr;  // $(anon NAME) values of this expansion
};

// Resolves one `$(TEXT)` whose TEXT has its `${...}` evaluated already; returns the replacement text.
// Throws ProcessError with the message a user can act on.
std::string resolve_substitution(const std::string& text, SubstitutionContext& context);

// roslaunch's convert_value(value, 'auto'): "1" -> int, "1.5" -> float, "true"/"False" -> bool, else the text.
class Value;
Value convert_auto(const std::string& value);

}  // namespace lcm_control::xacro
