// How a tool waits on the bus: Ctrl-C / SIGTERM as a flag that every bounded wait checks, sleeping to absolute
// monotonic deadlines, pumping the bus with a deadline, and request ids to match an answer to its request.
#pragma once

#include <cstdint>

#include "bus/bus.hpp"
#include "rt/stop_signal.hpp"  // install_stop_signals(), stop_requested(): what every wait here checks

namespace lcm_control::tools {

// Sleeps until the monotonic clock reaches deadline_us (bus/bus.hpp's
// monotonic_us()). Returns early when a stop is requested.
void sleep_until_us(int64_t deadline_us);

// Handles bus messages for up to timeout_ms. Throws on an LCM error; a wait cut
// short by Ctrl-C / SIGTERM is not one.
void handle_bus(Bus& bus, int timeout_ms);

// Handles bus messages until `done()` is true, a stop is requested, or
// timeout_s passes. Returns done().
template <class Pred>
bool pump_until(Bus& bus, Pred&& done, double timeout_s) {
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  while (!done()) {
    if (stop_requested()) return false;
    const int64_t left_ms = (end - monotonic_us()) / 1000;
    if (left_ms <= 0) return done();
    handle_bus(bus, int(left_ms < 50 ? left_ms : 50));
  }
  return true;
}

// A fresh id for matching an answer to its request (random, positive).
int64_t new_request_id();

}  // namespace lcm_control::tools
