// When the next message of a periodic stream (hardware/state in real time) is due, from the arrivals seen, so that a
// receiver can sleep to a little before it and take the tail without sleeping (controller_manager --spin-us): a
// timer or a datagram wakes a sleeping thread tens of microseconds late, a thread already running takes it at once.
// Times in microseconds on one clock (monotonic). Pure and allocation-free.
#pragma once

#include <algorithm>
#include <cstdint>

namespace lcm_control {

class ArrivalClock {
 public:
  // A message arrived at t_us; the stream's period is period_us (<= 0: not periodic, e.g. lockstep: nothing is
  // predicted until a period is given again).
  //
  // Arrivals are the sender's schedule plus a delay that is never negative, so an arrival before the prediction
  // moves it back to that arrival at once, one after it moves it forward by a sixteenth of the difference (the
  // prediction settles near the earliest arrivals and follows a sender whose clock runs slower), and one more than
  // a period late (a stall, a restart) starts over from it.
  void arrived(int64_t t_us, int64_t period_us) {
    if (period_us <= 0) {
      period_us_ = 0;
      return;
    }
    const bool restart = period_us_ != period_us || t_us <= expected_us_ || t_us - expected_us_ > period_us;
    expected_us_ = (restart ? t_us : expected_us_ + (t_us - expected_us_) / 16) + period_us;
    period_us_ = period_us;
  }
  // When the next message is expected; -1 when not known.
  int64_t next_us() const { return period_us_ > 0 ? expected_us_ : -1; }
  // How long a receiver may sleep at now_us, at most max_us, if it spins from spin_us before the expected arrival
  // to spin_us after it (then, the message late, it sleeps again until one arrives): 0 inside that window.
  int64_t sleep_us(int64_t now_us, int64_t spin_us, int64_t max_us) const {
    if (spin_us <= 0 || period_us_ <= 0 || now_us >= expected_us_ + spin_us) return max_us;
    return std::clamp<int64_t>(expected_us_ - spin_us - now_us, 0, max_us);
  }

 private:
  int64_t period_us_ = 0, expected_us_ = 0;
};

}  // namespace lcm_control
