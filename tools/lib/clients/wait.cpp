#include "tools/lib/clients/wait.hpp"

#include <fmt/format.h>
#include <time.h>

#include <cerrno>
#include <random>
#include <stdexcept>

namespace lcm_control::tools {

void sleep_until_us(int64_t deadline_us) {
  // monotonic_us() is steady_clock, which is CLOCK_MONOTONIC on Linux.
  timespec ts{};
  ts.tv_sec = deadline_us / 1000000;
  ts.tv_nsec = (deadline_us % 1000000) * 1000;
  while (!stop_requested()) {
    const int rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
    if (rc == 0) return;
    if (rc != EINTR) return;
  }
}

void handle_bus(Bus& bus, int timeout_ms) {
  if (!bus.handle(timeout_ms) && !stop_requested())
    throw std::runtime_error(fmt::format("LCM error while receiving on {}", bus.url()));
}

int64_t new_request_id() {
  static std::mt19937_64 rng{std::random_device{}()};
  return int64_t(rng() >> 1) | 1;
}

}  // namespace lcm_control::tools
