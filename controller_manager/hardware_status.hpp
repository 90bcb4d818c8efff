// What the controller manager last heard from the hardware it follows, for
// `cmctl list` and the spawner: session, mode, nominal and measured rate, and
// how long ago the last state came. seen() runs in the loop and only stores
// numbers; describe() is the text, pure.
#pragma once

#include <cstdint>
#include <string>

#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control::cm {

class HardwareStatus {
 public:
  void seen(const hardware_state_t& state, int64_t monotonic_us);  // a state the loop followed
  void close_window(int64_t monotonic_us);                        // measured rate over the window it ends
  int64_t age_us(int64_t monotonic_us) const { return any_ ? monotonic_us - last_us_ : -1; }  // -1: none yet

  // One line, e.g. "session 3fa9c2d1, real time, 1000 Hz (999.7 measured), step 5123, last state 0.001 s ago";
  // after silence_us without a state it says the loop is silent; states that repeat one step for longer than that
  // say the hardware is paused or waiting; with none, where it was expected.
  std::string describe(int64_t monotonic_us, int64_t silence_us, const std::string& state_channel,
                       const std::string& transport = "LCM URL") const;

 private:
  bool any_ = false, lockstep_ = false, e_stop_ = false;
  int64_t session_ = 0, step_ = 0, last_us_ = 0, step_since_us_ = 0, window_start_us_ = -1, in_window_ = 0;
  int32_t period_us_ = 0;
  double real_time_factor_ = 0, measured_hz_ = -1;
};

}  // namespace lcm_control::cm
