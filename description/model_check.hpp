// Cross-checks of a loaded robot model (URDF joints and limits, transmissions,
// pid_gains against the URDF): problems that stop the servers, warnings worth
// saying once, and hints doctor prints about things that are valid but often
// not what was meant.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

// Adds every problem to `problems`, warnings to model.warnings and hints to model.hints.
void check_model(RobotModel& model, std::vector<std::string>& problems);
// The same, throwing ModelError listing every problem.
void validate(RobotModel& model);

}  // namespace lcm_control
