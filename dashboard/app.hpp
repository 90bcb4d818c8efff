// The dashboard program's work (dashboard/main.cpp parses the flags into Options and calls run): serve the page, the
// robot's files and the bus to browsers until Ctrl-C or --duration.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::dashboard {

struct Options {
  BusFlags bus;
  std::string bind = "127.0.0.1", web_root, urdf;
  std::vector<std::string> package_path, xacro_args;
  int port = 8080, nice = 10;
  double rate_hz = 30, duration_s = 0, timeout_s = 5;
  bool read_only = false;
};

// Returns the exit code; throws as run_program expects (runtime_error: no page, no URDF, no port).
int run(Options& o);

}  // namespace lcm_control::dashboard
