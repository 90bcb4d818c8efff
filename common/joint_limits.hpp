// Command saturation as joint_limits_interface does it: position commands
// rate-limited by the velocity limit and clamped to the position limits,
// velocity and effort commands clamped to their limits. Real-time safe.
#pragma once

#include <algorithm>
#include <cmath>

namespace lcm_control {

struct JointLimits {
  bool has_position = false;
  double lower = 0, upper = 0;
  double max_velocity = INFINITY;  // > 0
  double max_effort = INFINITY;    // > 0
};

// PositionJointSaturationHandle: cmd in [prev - v*dt, prev + v*dt] and in [lower, upper].
class PositionSaturation {
 public:
  explicit PositionSaturation(const JointLimits& l = {}) : limits_(l) {}
  void reset(double current_position) { prev_ = current_position; primed_ = true; }
  bool primed() const { return primed_; }
  double enforce(double cmd, double dt) {
    if (!primed_) reset(cmd);
    double lo = prev_ - limits_.max_velocity * dt, hi = prev_ + limits_.max_velocity * dt;
    if (limits_.has_position) {
      lo = std::max(lo, limits_.lower);
      hi = std::min(hi, limits_.upper);
      if (lo > hi) lo = hi = std::clamp(prev_, limits_.lower, limits_.upper);
    }
    prev_ = std::clamp(cmd, lo, hi);
    return prev_;
  }
  double last() const { return prev_; }

 private:
  JointLimits limits_;
  double prev_ = 0;
  bool primed_ = false;
};

inline double clamp_abs(double v, double limit) { return std::clamp(v, -limit, limit); }

}  // namespace lcm_control
