// Command limits as joint_limits_interface enforces them: saturation
// (position commands rate-limited by the velocity limit and clamped to the
// position limits, velocity and effort commands clamped to their limits) and
// soft limits (URDF <safety_controller>), which bound the command so that the
// joint is pushed back as it nears or passes a soft limit. Real-time safe.
#pragma once

#include <algorithm>
#include <cmath>
#include <utility>

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

// URDF <safety_controller soft_lower_limit soft_upper_limit k_position k_velocity> (rad or m; 1/s; N*m*s/rad or N*s/m).
struct SoftLimits {
  double lower = 0, upper = 0;
  double k_position = 0, k_velocity = 0;
};

// The velocities allowed at `position` (rad/s or m/s): -k_position * (position - soft limit) for each side, within
// +-max_velocity; +-max_velocity for a joint without position limits (continuous).
inline std::pair<double, double> soft_velocity_bounds(const JointLimits& l, const SoftLimits& s, double position) {
  if (!l.has_position) return {-l.max_velocity, l.max_velocity};
  return {clamp_abs(-s.k_position * (position - s.lower), l.max_velocity),
          clamp_abs(-s.k_position * (position - s.upper), l.max_velocity)};
}

// PositionJointSoftLimitsHandle: open loop on the previous command (the measured position only primes it): the
// command moves at most the soft velocity bounds times dt from the previous one, and stays within the hard limits.
class PositionSoftLimits {
 public:
  void reset() { primed_ = false; }
  double enforce(const JointLimits& l, const SoftLimits& s, double cmd, double position, double dt) {
    if (!primed_) prev_ = position, primed_ = true;
    const auto [v_lo, v_hi] = soft_velocity_bounds(l, s, prev_);
    double lo = prev_ + v_lo * dt, hi = prev_ + v_hi * dt;
    if (l.has_position) lo = std::max(lo, l.lower), hi = std::min(hi, l.upper);
    prev_ = std::clamp(cmd, std::min(lo, hi), hi);
    return prev_;
  }

 private:
  double prev_ = 0;
  bool primed_ = false;
};

// EffortJointSoftLimitsHandle: efforts within -k_velocity * (velocity - soft velocity bound) for each side, within
// +-max_effort, from the measured position and velocity.
inline double effort_soft_limits(const JointLimits& l, const SoftLimits& s, double cmd, double position,
                                 double velocity) {
  const auto [v_lo, v_hi] = soft_velocity_bounds(l, s, position);
  const double lo = clamp_abs(-s.k_velocity * (velocity - v_lo), l.max_effort);
  const double hi = clamp_abs(-s.k_velocity * (velocity - v_hi), l.max_effort);
  return std::clamp(cmd, std::min(lo, hi), hi);
}

// VelocityJointSoftLimitsHandle (no acceleration limits in a URDF): the soft velocity bounds at the measured position.
inline double velocity_soft_limits(const JointLimits& l, const SoftLimits& s, double cmd, double position) {
  const auto [lo, hi] = soft_velocity_bounds(l, s, position);
  return std::clamp(cmd, std::min(lo, hi), hi);
}

}  // namespace lcm_control
