// The robot model as text, the way doctor prints it: links, joints, each
// transmission's interface and what the hardware does with it, controllers,
// then warnings and hints.
#pragma once

#include <string>

#include "description/robot_model.hpp"

namespace lcm_control {

std::string describe(const RobotModel& model);

}  // namespace lcm_control
