#include "tools/lib/gripper_goal.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "description/text.hpp"
#include "lcm_control/gripper_command_t.hpp"
#include "lcm_control/gripper_status_t.hpp"

namespace lcm_control::tools {

namespace {

// The program that commands what `c` takes.
std::string commanded_with(const controller_info_t& c) {
  if (c.command_type == "joint_trajectory_t") return fmt::format("send-trajectory {} ...", c.name);
  if (c.command_type == "twist_t") return fmt::format("drive {} ...", c.name);
  if (c.command_type == "float64_t" || c.command_type == "float64_array_t")
    return fmt::format("turret-cmd {} VALUE...", c.name);
  return "";
}

}  // namespace

const controller_info_t& gripper_controller(const std::vector<controller_info_t>& listed, const std::string& name) {
  std::vector<std::string> names;
  for (const auto& c : listed) {
    if (c.name != name) {
      names.push_back(c.name);
      continue;
    }
    if (c.command_type != gripper_command_t::getTypeName()) {
      const std::string takes = c.command_type.empty()
                                    ? std::string("takes no commands")
                                    : fmt::format("takes {} on '{}/{}'", c.command_type, name, c.command_channel);
      const std::string instead = commanded_with(c);
      throw std::runtime_error(fmt::format("'{}' is a {} and {}, not gripper_command_t goals (a GripperActionController "
                                           "does){}",
                                           name, c.type, takes, instead.empty() ? "" : "; command it with " + instead));
    }
    if (c.state != "running")
      throw std::runtime_error(fmt::format("'{}' is loaded but {}, not running: start it with `cmctl start {}`", name,
                                           c.state, name));
    return c;
  }
  const std::string close = closest_name(name, names, 3);
  throw std::runtime_error(fmt::format(
      "no controller '{}' in the controller manager ({}): load and start it with `spawner {}` (a controller of the "
      "YAML with type position_controllers/, effort_controllers/ or "
      "parallel_gripper_action_controller/GripperActionController){}",
      name, names.empty() ? "none loaded" : fmt::format("loaded: {}", fmt::join(names, ", ")), name,
      close.empty() ? "" : "; did you mean '" + close + "'?"));
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
