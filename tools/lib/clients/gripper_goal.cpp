#include "tools/lib/clients/gripper_goal.hpp"

#include <fmt/format.h>

#include "lcm_control/gripper_command_t.hpp"
#include "lcm_control/gripper_status_t.hpp"
#include "tools/lib/clients/command_check.hpp"

namespace lcm_control::tools {

const controller_info_t& gripper_controller(const std::vector<controller_info_t>& listed, const std::string& name,
                                           const std::string& prefix) {
  return commandable(listed, name, {gripper_command_t::getTypeName(), 0},
                     "(a controller of the YAML with type position_controllers/, effort_controllers/ or "
                     "parallel_gripper_action_controller/GripperActionController)",
                     prefix);
}

std::string gripper_status_name(int8_t status) {
  switch (status) {
    case gripper_status_t::ACTIVE: return "ACTIVE";
    case gripper_status_t::SUCCEEDED: return "SUCCEEDED";
    case gripper_status_t::REJECTED: return "REJECTED";
    case gripper_status_t::ABORTED: return "ABORTED";
    case gripper_status_t::PREEMPTED: return "PREEMPTED";
  }
  return fmt::format("status {}", status);
}

}  // namespace lcm_control::tools
