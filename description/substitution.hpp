// roslaunch's substitution args in launch files and in ros_control YAML
// (rosparam's subst_value): $(find PKG), $(arg NAME), $(env VAR),
// $(optenv VAR [default]), $(eval EXPR) (xacro's evaluator, with the args,
// arg(), find(), env(), optenv()); and ROS 2 launch's $(var NAME), read as $(arg NAME).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace lcm_control {

struct Substitutions {
  std::vector<std::string> package_path;                     // for $(find); empty: default_package_path()
  std::vector<std::pair<std::string, std::string>> args;     // for $(arg), later entries win
  // What the user does when an $(arg NAME) has no value; "{0}" stands for NAME.
  std::string missing_arg_fix = "give it a value";
};

// Throws ModelError (prefixed with `where`) for an unknown package, arg, variable or substitution.
std::string substitute(const std::string& text, const Substitutions& subs, const std::string& where);
// The same for a whole YAML file, line by line, so that a message names `file:LINE`; comment lines are left as
// they are.
std::string substitute_file(const std::string& text, const Substitutions& subs, const std::string& file);
// "NAME=VALUE" or roslaunch's "NAME:=VALUE"; throws std::invalid_argument otherwise.
std::pair<std::string, std::string> parse_arg(const std::string& assignment);

}  // namespace lcm_control
