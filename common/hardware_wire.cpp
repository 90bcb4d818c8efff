#include "common/hardware_wire.hpp"

#include "common/wire_check.hpp"
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

std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators) {
  return wire_problem<hardware_state_t>(data, size, max_actuators, "the robot's actuators");
}

std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators) {
  return wire_problem<hardware_command_t>(data, size, max_actuators, "the robot's actuators");
}

}  // namespace lcm_control
