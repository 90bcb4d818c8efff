// What both ends of the hardware loop share about its two messages: the wire
// mode of an interface and its name, matching actuators by name (once per
// session, then indices: docs/hardware-protocol.md), and the schema walk of
// bus/wire_check.hpp for hardware/state and hardware/command with
// num_actuators also bounded by the robot's actuators, run on those bytes
// before decoding them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

// hardware_command_t::MODE_POSITION, _VELOCITY or _EFFORT for an interface.
int8_t wire_mode(Interface i);
// "position", "velocity", "effort" or "none" (MODE_NONE and anything unknown).
const char* wire_mode_name(int mode);

// A hardware message's actuators matched by name to ours. slot[k]: the message's index of ours[k], or -1 (listed in
// `missing`); the message's names that are not ours are in `unknown`, those it lists twice in `repeated`.
struct ActuatorBinding {
  std::vector<int> slot;
  std::vector<std::string> missing, unknown, repeated;
  // "" when every one of ours is there exactly once (unknown ones are allowed only with `allow_unknown`); else what
  // differs, naming the actuators.
  std::string problem(bool allow_unknown) const;
};
ActuatorBinding bind_actuators(const std::vector<std::string>& ours, const std::vector<std::string>& theirs);

// "" when the bytes can be the message with num_actuators between 0 and max_actuators (a state's sensor values
// between 0 and max_sensor_values too); else why not.
std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators, int max_sensor_values = 0);
std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators, int max_gpio_commands = 0);

}  // namespace lcm_control
