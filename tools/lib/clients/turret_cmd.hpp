// turret-cmd: commands to a controller from muparser expressions in i and t (rqt's Message Publisher): once, at a
// rate of wall time, or on sim time (a command source in the controller manager for a controller TARGET).
// tools/turret_cmd.cpp parses the flags and calls run_turret_cmd.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct TurretCmdFlags {
  std::string target;
  std::vector<std::string> exprs;
  double rate = 0;
  int64_t count = 0;
  double duration = 0;
  bool raw_channel = false, array = false, sim_time = false, print = false;
  double timeout = 5;  // for sim time, and for the controller manager's answer
  BusFlags bus;
};

void add_turret_cmd_flags(CLI::App& app, TurretCmdFlags& o);

int run_turret_cmd(const TurretCmdFlags& o);

}  // namespace lcm_control::tools
