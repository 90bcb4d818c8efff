// `$(...)` substitution args, the one engine of both dialects: xacro's (arg, find, env, optenv, eval, dirname, cwd,
// anon: the rules of xacro's substitution_args.py, with $(dirname) the folder of the file being read and $(anon) as
// ROS 1 had it) and roslaunch's in a rosparam YAML (find, arg, ROS 2 launch's var for arg, env, optenv, eval). The
// caller may word the refusals for its own users (SubstitutionMessages).
#pragma once

#include <functional>
#include <map>
#include <string>

namespace lcm_control::xacro {

enum class Dialect {
  Xacro,     // every command, and a $(find) an arg's value brought in resolved in a second pass (xacro 2.0.10)
  RosParam,  // find, arg (and var), env, optenv, eval: a launch file's and a rosparam YAML's, one pass
};

// How a refusal is worded (nullptr: xacro's own words). Each gets what the user wrote.
struct SubstitutionMessages {
  std::function<std::string(const std::string& command, const std::string& name)> missing_arg;
  std::function<std::string(const std::string& package)> missing_package;
  std::function<std::string(const std::string& variable)> missing_env;
  std::function<std::string(const std::string& whole)> unsupported;  // `$(...)` as written
};

struct SubstitutionContext {
  Dialect dialect = Dialect::Xacro;
  SubstitutionMessages messages;
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
