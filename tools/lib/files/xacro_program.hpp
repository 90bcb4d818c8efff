// xacro: a .xacro robot description expanded into the document the official ROS xacro prints (or the files it reads, or its budget use), to stdout or a file.
// tools/xacro.cpp parses the flags and calls run_xacro.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct XacroFlags {
  std::vector<std::string> positional, package_path;  // the file, then NAME:=VALUE
  std::string output;
  bool deps = false, inorder = false, stats = false;
  double budget = 0;
};

void add_xacro_flags(CLI::App& app, XacroFlags& f);

int run_xacro(const XacroFlags& f);

}  // namespace lcm_control::tools
