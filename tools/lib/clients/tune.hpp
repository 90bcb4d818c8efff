// tune: dynamic reconfigure for PID gains: the gains in force for a joint, or some of them set and confirmed from
// the owner's answer (sim_server for gazebo_ros_control/pid_gains, or a controller with its own PID).
#pragma once

#include <optional>
#include <string>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct TuneFlags {
  std::string joint, owner = channels::kSimGainsOwner;
  std::optional<double> p, i, d, i_clamp;
  std::optional<bool> antiwindup;
  double timeout = 3;
  BusFlags bus;
};

void add_tune_flags(CLI::App& app, TuneFlags& f);

int run_tune(const TuneFlags& f);

}  // namespace lcm_control::tools
