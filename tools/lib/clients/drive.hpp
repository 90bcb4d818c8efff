// drive: teleop for a mobile base: twist_t on <controller>/cmd_vel at a fixed rate of wall time from expressions in i and t, a zero twist at the end.
// tools/drive.cpp parses the flags and calls run_drive.
#pragma once

#include <string>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct DriveFlags {
  std::string controller, linear, angular, lateral = "0";  // expressions in i and t
  double rate = 20, duration = 0;
  BusFlags bus;
};

void add_drive_flags(CLI::App& app, DriveFlags& f);

int run_drive(const DriveFlags& f);

}  // namespace lcm_control::tools
