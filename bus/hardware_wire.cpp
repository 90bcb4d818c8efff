#include "bus/hardware_wire.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "bus/wire_check.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control {

int8_t wire_mode(Interface i) {
  switch (i) {
    case Interface::Position: return hardware_command_t::MODE_POSITION;
    case Interface::Velocity: return hardware_command_t::MODE_VELOCITY;
    case Interface::Effort: return hardware_command_t::MODE_EFFORT;
  }
  return hardware_command_t::MODE_NONE;
}

const char* wire_mode_name(int mode) {
  switch (mode) {
    case hardware_command_t::MODE_POSITION: return "position";
    case hardware_command_t::MODE_VELOCITY: return "velocity";
    case hardware_command_t::MODE_EFFORT: return "effort";
  }
  return "none";
}

ActuatorBinding bind_actuators(const std::vector<std::string>& ours, const std::vector<std::string>& theirs) {
  ActuatorBinding b;
  b.slot.assign(ours.size(), -1);
  for (size_t i = 0; i < theirs.size(); ++i) {
    size_t k = 0;
    while (k < ours.size() && ours[k] != theirs[i]) ++k;
    if (k == ours.size()) {
      b.unknown.push_back(theirs[i]);
    } else if (b.slot[k] >= 0) {
      b.repeated.push_back(theirs[i]);
    } else {
      b.slot[k] = static_cast<int>(i);
    }
  }
  for (size_t k = 0; k < ours.size(); ++k)
    if (b.slot[k] < 0) b.missing.push_back(ours[k]);
  return b;
}

std::string ActuatorBinding::problem(bool allow_unknown) const {
  std::vector<std::string> p;
  if (!missing.empty()) p.push_back(fmt::format("missing actuator(s) '{}'", fmt::join(missing, "', '")));
  if (!allow_unknown && !unknown.empty())
    p.push_back(fmt::format("unknown actuator(s) '{}'", fmt::join(unknown, "', '")));
  if (!repeated.empty()) p.push_back(fmt::format("actuator(s) '{}' listed twice", fmt::join(repeated, "', '")));
  return fmt::format("{}", fmt::join(p, "; "));
}

std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators, int max_sensor_values) {
  if (max_sensor_values <= max_actuators)
    return wire_problem<hardware_state_t>(data, size, max_actuators, "the robot's actuators");
  return wire_problem<hardware_state_t>(data, size, max_sensor_values, "the robot's actuators and sensor values");
}

std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators, int max_gpio_commands) {
  if (max_gpio_commands <= max_actuators)
    return wire_problem<hardware_command_t>(data, size, max_actuators, "the robot's actuators");
  return wire_problem<hardware_command_t>(data, size, max_gpio_commands, "the robot's actuators and GPIO commands");
}

}  // namespace lcm_control
