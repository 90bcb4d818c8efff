// Checks on the raw bytes of hardware/state and hardware/command before they
// are decoded: lcm-gen's decoders trust the array counts, so a negative count
// throws from inside the LCM handler and a huge one allocates millions of
// elements before the decoder finds the buffer too short.
#pragma once

#include <cstddef>
#include <string>

namespace lcm_control {

// "" when the message's num_actuators is between 0 and max_actuators and fits in `size` bytes; else why not.
std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators);
std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators);

}  // namespace lcm_control
