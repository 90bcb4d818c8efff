// One time base for what tools stamp and join: a message's utime is either
// sim_server's sim time (microseconds since the simulation started) or the wall
// clock (microseconds since 1970). Commands from our tools carry sim time when
// sim_server's `clock` is on the bus; tools that join channels by utime refuse
// to mix the two.
#pragma once

#include <cstdint>
#include <string>

#include "bus/bus.hpp"
#include "lcm_control/sim_clock_t.hpp"

namespace lcm_control::tools {

enum class TimeBase { Sim, Wall };

// Wall from 1e15 us (September 2001) on: a simulation would need 31 years of sim time to get there.
TimeBase time_base(int64_t utime);
const char* time_base_name(TimeBase b);  // "sim time" or "wall-clock time"

// "" when both utimes are on one clock; else a sentence naming both channels and their clocks.
std::string mixed_clocks(const std::string& channel_a, int64_t utime_a, const std::string& channel_b,
                         int64_t utime_b);

// Stamps for the commands a tool publishes: the newest sim time on `clock` when sim_server is on the bus (so that
// commands and joint_states share a clock), else the wall clock. Sim time advances only while the bus is handled.
class CommandClock {
 public:
  // Subscribes to `clock` (namespaced) and handles the bus up to wait_s for a first message.
  CommandClock(Bus& bus, double wait_s);
  ~CommandClock();
  CommandClock(const CommandClock&) = delete;
  CommandClock& operator=(const CommandClock&) = delete;

  bool on_sim() const { return sim_utime_ >= 0; }
  int64_t now_us() const { return on_sim() ? sim_utime_ : wall_us(); }

 private:
  void on_clock(const lcm::ReceiveBuffer*, const std::string&, const sim_clock_t* m);
  Bus& bus_;
  int sub_ = 0;
  int64_t sim_utime_ = -1;
};

}  // namespace lcm_control::tools
