// doctor: a robot's files checked as sim_server and controller_manager will load them, or as `launch FILE` will start
// them: the model described, every configured controller loaded in-process as controller_manager would load it, and
// every problem named. tools/doctor.cpp parses the flags and calls run_doctor.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct DoctorFlags {
  RobotFileFlags files;                  // --urdf is required unless a launch FILE is given
  std::vector<std::string> positional;  // a launch FILE, then NAME:=VALUE for its <arg>s
  std::string ns;
  bool strict = false;
  std::vector<std::string> to_start;  // --controllers
};

void add_doctor_flags(CLI::App& app, DoctorFlags& f);

// Exit 0 when the servers would take the files and every controller to start loads; 3 (problems on stderr) when not.
int run_doctor(const DoctorFlags& f);

}  // namespace lcm_control::tools
