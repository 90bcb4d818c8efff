// Microseconds on the monotonic clock (periods, deadlines) and on the wall clock (message stamps).
#pragma once

#include <cstdint>

namespace lcm_control {

int64_t monotonic_us();
int64_t wall_us();

}  // namespace lcm_control
