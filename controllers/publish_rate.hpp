// A broadcaster's rate on the hardware clock: due() once per 1/hz (every cycle for hz 0), first on the first cycle
// after start(); no burst to catch up after falling behind, and due again at once after a backward time jump.
#pragma once

namespace lcm_control::cm {

struct PublishRate {
  double hz = 0;  // 0: every cycle

  void start(double t) {
    if (hz > 0) last_ = t - 1.001 / hz;
  }
  bool due(double t) {
    if (hz <= 0) return true;
    const double dt = 1.0 / hz;
    if (t < last_) last_ = t - 1.001 * dt;
    if (!(last_ + dt < t)) return false;
    last_ += dt;
    if (t - last_ > dt) last_ = t;  // fell behind (time jump, slow loop)
    return true;
  }

 private:
  double last_ = 0;
};

}  // namespace lcm_control::cm
