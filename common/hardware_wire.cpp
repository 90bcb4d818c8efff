#include "common/hardware_wire.hpp"

#include "common/wire_check.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control {

std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators) {
  return wire_problem<hardware_state_t>(data, size, max_actuators, "the robot's actuators");
}

std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators) {
  return wire_problem<hardware_command_t>(data, size, max_actuators, "the robot's actuators");
}

}  // namespace lcm_control
