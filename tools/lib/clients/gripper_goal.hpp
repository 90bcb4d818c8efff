// What the `gripper` tool (and its tests) need to send a GripperActionController a goal: the check that a
// controller the manager lists takes gripper_command_t goals, and gripper_status_t's status names.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lcm_control/controller_info_t.hpp"

namespace lcm_control::tools {

// `name` among the controllers the manager lists, if it is running and takes gripper_command_t goals; else
// std::runtime_error naming the controller, what it takes, and what to do instead (command_check.hpp's commandable).
const controller_info_t& gripper_controller(const std::vector<controller_info_t>& listed, const std::string& name,
                                           const std::string& prefix = "");

// gripper_status_t's constant names: "SUCCEEDED", "ABORTED", ...
std::string gripper_status_name(int8_t status);

}  // namespace lcm_control::tools
