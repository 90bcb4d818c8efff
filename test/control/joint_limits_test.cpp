// Soft limits (URDF <safety_controller>) against joint_limits_interface's formulas, one interface each.
#include "control/joint_limits.hpp"

#include <gtest/gtest.h>

namespace lcm_control {
namespace {

// A revolute joint with limits [-2, 2], 1 rad/s, 10 N*m and soft limits [-0.5, 0.5], k_position 10, k_velocity 20.
JointLimits limits() {
  JointLimits l;
  l.has_position = true;
  l.lower = -2;
  l.upper = 2;
  l.max_velocity = 1;
  l.max_effort = 10;
  return l;
}
const SoftLimits kSoft{-0.5, 0.5, 10, 20};

TEST(SoftLimits, VelocityBoundsPushBackNearAndBeyondTheSoftLimits) {
  auto [lo, hi] = soft_velocity_bounds(limits(), kSoft, 0.0);  // far inside: the velocity limit
  EXPECT_DOUBLE_EQ(lo, -1);
  EXPECT_DOUBLE_EQ(hi, 1);
  std::tie(lo, hi) = soft_velocity_bounds(limits(), kSoft, 0.45);  // -10 * (0.45 - 0.5) = 0.5
  EXPECT_DOUBLE_EQ(hi, 0.5);
  EXPECT_DOUBLE_EQ(lo, -1);
  std::tie(lo, hi) = soft_velocity_bounds(limits(), kSoft, 0.52);  // beyond: both sides negative, -0.2
  EXPECT_NEAR(hi, -0.2, 1e-12);
  EXPECT_DOUBLE_EQ(lo, -1);
  JointLimits continuous = limits();
  continuous.has_position = false;
  std::tie(lo, hi) = soft_velocity_bounds(continuous, kSoft, 100.0);
  EXPECT_DOUBLE_EQ(lo, -1);
  EXPECT_DOUBLE_EQ(hi, 1);
}

TEST(SoftLimits, PositionCommandsMoveFromThePreviousCommandWithinTheBounds) {
  PositionSoftLimits p;
  const double dt = 0.01;
  // First call primes from the measured position (0.4): bound 0.4 + (-10 * (0.4 - 0.5)) * dt = 0.41.
  EXPECT_NEAR(p.enforce(limits(), kSoft, 5.0, 0.4, dt), 0.41, 1e-12);
  // Open loop: the previous command (0.41), not the measured position, sets the next bound: 0.41 + 0.9 * 0.01.
  EXPECT_NEAR(p.enforce(limits(), kSoft, 5.0, -1.0, dt), 0.419, 1e-12);
  // Inside the bounds a command passes unchanged; going down is bounded by the velocity limit.
  EXPECT_DOUBLE_EQ(p.enforce(limits(), kSoft, 0.415, 0.0, dt), 0.415);
  EXPECT_NEAR(p.enforce(limits(), kSoft, -5.0, 0.0, dt), 0.405, 1e-12);
  // Held at a command, it converges to the soft limit and never passes it.
  double cmd = 0;
  for (int k = 0; k < 2000; ++k) cmd = p.enforce(limits(), kSoft, 5.0, 0.0, dt);
  EXPECT_LE(cmd, 0.5);
  EXPECT_NEAR(cmd, 0.5, 1e-9);
  // Primed beyond the soft limit (a joint pushed there), every command moves back towards it.
  PositionSoftLimits q;
  EXPECT_NEAR(q.enforce(limits(), kSoft, 0.8, 0.8, dt), 0.8 - 1 * dt, 1e-12);  // v_hi = sat(-10 * 0.3) = -1
  // And the hard limits bound it: soft limits beyond the hard ones change nothing past them.
  PositionSoftLimits r;
  const SoftLimits wide{-5, 5, 10, 20};
  EXPECT_DOUBLE_EQ(r.enforce(limits(), wide, 3.0, 1.995, dt), 2.0);
  q.reset();
  EXPECT_DOUBLE_EQ(q.enforce(limits(), kSoft, 0.0, 0.0, dt), 0.0);  // primed again from the measured position
}

TEST(SoftLimits, EffortFromTheMeasuredPositionAndVelocity) {
  // Inside, at rest: -20 * (0 - (+-1)) = +-20, within +-10 N*m: the effort limit.
  EXPECT_DOUBLE_EQ(effort_soft_limits(limits(), kSoft, 50.0, 0.0, 0.0), 10.0);
  EXPECT_DOUBLE_EQ(effort_soft_limits(limits(), kSoft, -50.0, 0.0, 0.0), -10.0);
  EXPECT_DOUBLE_EQ(effort_soft_limits(limits(), kSoft, 3.0, 0.0, 0.0), 3.0);
  // Near the upper soft limit, moving up at 0.4 rad/s: v_hi = 0.5, so at most -20 * (0.4 - 0.5) = 2 N*m.
  EXPECT_NEAR(effort_soft_limits(limits(), kSoft, 8.0, 0.45, 0.4), 2.0, 1e-12);
  // Beyond it, at rest: v_hi = -0.2, so at most -20 * (0 + 0.2) = -4: pushed back whatever is asked.
  EXPECT_NEAR(effort_soft_limits(limits(), kSoft, 8.0, 0.52, 0.0), -4.0, 1e-12);
}

TEST(SoftLimits, VelocityFromTheMeasuredPosition) {
  EXPECT_DOUBLE_EQ(velocity_soft_limits(limits(), kSoft, 3.0, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(velocity_soft_limits(limits(), kSoft, -0.3, 0.0), -0.3);
  EXPECT_NEAR(velocity_soft_limits(limits(), kSoft, 3.0, 0.45), 0.5, 1e-12);
  EXPECT_NEAR(velocity_soft_limits(limits(), kSoft, 3.0, 0.52), -0.2, 1e-12);
  EXPECT_NEAR(velocity_soft_limits(limits(), kSoft, -3.0, -0.6), 1.0, 1e-12);  // below the lower: only upward
}

}  // namespace
}  // namespace lcm_control
