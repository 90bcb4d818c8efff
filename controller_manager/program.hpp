// controller_manager as a program: its flags, and the run (load the robot, serve the loop and requests between
// cycles until SIGINT/SIGTERM, then stop and unload everything). main() parses the flags and calls
// run_controller_manager. Exit codes: 0 clean stop, 2 usage, 3 bad URDF/YAML, 4 LCM.
#pragma once

#include <cstdint>

#include "cli/cli.hpp"

namespace lcm_control::cm {

struct ProgramFlags {
  RobotProcessFlags robot;
  double silence_s = 0.25;
  int64_t spin_us = 0;
  bool quiet_model = false;
};

void add_program_flags(CLI::App& app, ProgramFlags& f);

int run_controller_manager(const ProgramFlags& f);

}  // namespace lcm_control::cm
