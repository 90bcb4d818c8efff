// The schema walk of common/wire_check.hpp for hardware/state and
// hardware/command, with num_actuators also bounded by the robot's actuators:
// what the two processes run on those bytes before decoding them.
#pragma once

#include <cstddef>
#include <string>

namespace lcm_control {

// "" when the bytes can be the message with num_actuators between 0 and max_actuators; else why not.
std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators);
std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators);

}  // namespace lcm_control
