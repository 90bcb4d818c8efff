#include "common/hardware_wire.hpp"

#include <fmt/format.h>

#include <cstdint>

namespace lcm_control {

namespace {

// num_actuators is a big-endian int32 at `offset`; each actuator takes at least `per_actuator` bytes after it.
std::string check_count(const void* data, size_t size, size_t offset, size_t per_actuator, int max_actuators,
                        const char* type) {
  if (size < offset + 4) return fmt::format("{} bytes: too short for a {}", size, type);
  const auto* p = static_cast<const uint8_t*>(data) + offset;
  const int32_t n = int32_t(uint32_t(p[0]) << 24 | uint32_t(p[1]) << 16 | uint32_t(p[2]) << 8 | uint32_t(p[3]));
  if (n < 0 || n > max_actuators)
    return fmt::format("num_actuators {} is not between 0 and {} (the robot's actuators)", n, max_actuators);
  if (size_t(n) * per_actuator > size - offset - 4)
    return fmt::format("num_actuators {} does not fit in {} bytes", n, size);
  return "";
}

}  // namespace

// Offsets after the 8-byte fingerprint; per actuator at least an empty name (4-byte length + NUL), the mode and
// the doubles.
std::string check_hardware_state_bytes(const void* data, size_t size, int max_actuators) {
  return check_count(data, size, 8 + 8 + 8 + 8 + 1 + 4 + 1 + 8, 5 + 1 + 3 * 8, max_actuators, "hardware_state_t");
}

std::string check_hardware_command_bytes(const void* data, size_t size, int max_actuators) {
  return check_count(data, size, 8 + 8 + 8 + 8, 5 + 1 + 8, max_actuators, "hardware_command_t");
}

}  // namespace lcm_control
