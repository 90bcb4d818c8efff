// xacro without ROS: expands a robot's .urdf.xacro (macros, properties, includes, ${...} expressions, $(...)
// substitution args, xacro.load_yaml) into the document the official xacro (ros2 branch, 2.0.10) prints.
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "xacro/budget.hpp"

namespace lcm_control::xacro {

struct Options {
  std::vector<std::pair<std::string, std::string>> args;                // name:=value from the command line, in order
  std::function<std::string(const std::string& package)> find_package;  // the package's folder for $(find), "" if absent
  std::string package_search_note;  // appended to a "package not found" error: the folders searched and how to add one
  std::function<void(const std::string& line)> message;  // xacro.message/warning output and warnings; default: stderr
  Budget budget;  // what the expansion may build; crossing it is an XacroError naming the budget
};

struct Expansion {
  std::string xml;                      // the expanded document, formatted as the official xacro prints it
  std::vector<std::string> files_read;  // every file read (xacro sources and YAML), as --deps lists them
  BudgetUse budget_use;                 // what it built, against Options::budget
};

// A problem in the input: what(): the whole message, several lines: the problem with file:line, then the chain of
// macro calls and includes that led there.
class XacroError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Expands the file. An argument with an empty value (`name:=`) is ignored, as the official xacro's command line
// ignores it. files_read starts with `path` itself; the official `--deps` lists the others.
// Throws XacroError.
Expansion expand_file(const std::string& path, const Options& options);

// "name:=value" -> {name, value} (both trimmed of spaces, as xacro's command line does). Throws
// std::invalid_argument naming the text when there is no `:=`, the name is empty, or `:=` appears twice.
std::pair<std::string, std::string> parse_arg(const std::string& text);

// Whether path names a xacro file (.xacro, .urdf.xacro, .xacro.urdf, ...): its name contains ".xacro".
bool is_xacro(const std::string& path);

}  // namespace lcm_control::xacro
