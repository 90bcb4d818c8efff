#include "control/pid.hpp"

#include <gtest/gtest.h>

#include <cmath>

using lcm_control::Pid;
using lcm_control::PidGains;

TEST(Pid, ProportionalOnly) {
  Pid pid(PidGains{150, 0, 0, 0, 0, false});
  EXPECT_DOUBLE_EQ(pid.compute(0.5, 0.001), 75.0);
}

TEST(Pid, NoDerivativeKickOnFirstSample) {
  Pid pid(PidGains{1, 0, 10, 0, 0, false});
  EXPECT_DOUBLE_EQ(pid.compute(1.0, 0.001), 1.0);  // ros_control would add d*e/dt = 10000
  EXPECT_DOUBLE_EQ(pid.compute(1.5, 0.001), 1.5 + 10 * 0.5 / 0.001);
  pid.reset();
  EXPECT_DOUBLE_EQ(pid.compute(2.0, 0.001), 2.0);
}

TEST(Pid, IntegralIsZeroWithoutIClampLikeControlToolbox) {
  Pid pid(PidGains{0, 5, 0, 0, 0, false});
  for (int k = 0; k < 100; ++k) EXPECT_DOUBLE_EQ(pid.compute(1.0, 0.01), 0.0);
}

TEST(Pid, IntegralClampedWithoutAntiwindupButIntegratorKeepsGrowing) {
  Pid pid(PidGains{0, 1, 0, -0.5, 0.5, false});
  double cmd = 0;
  for (int k = 0; k < 100; ++k) cmd = pid.compute(1.0, 0.01);
  EXPECT_DOUBLE_EQ(cmd, 0.5);
  EXPECT_NEAR(pid.integral(), 1.0, 1e-9);  // hidden integrator wound up
  // Error reverses: output stays clamped until the wound-up integral unwinds.
  cmd = pid.compute(-1.0, 0.01);
  EXPECT_DOUBLE_EQ(cmd, 0.5);
}

TEST(Pid, AntiwindupClampsTheIntegrator) {
  Pid pid(PidGains{0, 2, 0, -0.5, 0.5, true});
  double cmd = 0;
  for (int k = 0; k < 100; ++k) cmd = pid.compute(1.0, 0.01);
  EXPECT_DOUBLE_EQ(cmd, 0.5);
  EXPECT_DOUBLE_EQ(pid.integral(), 0.25);
  cmd = pid.compute(-1.0, 0.01);
  EXPECT_NEAR(cmd, 2 * (0.25 - 0.01), 1e-12);  // unwinds at once
}

TEST(Pid, ExplicitErrorDerivative) {
  Pid pid(PidGains{2, 0, 0.5, 0, 0, false});
  EXPECT_DOUBLE_EQ(pid.compute(1.0, -4.0, 0.001), 2.0 - 2.0);
}

TEST(Pid, ZeroDtOrNanGivesZero) {
  Pid pid(PidGains{2, 0, 0.5, 0, 0, false});
  EXPECT_EQ(pid.compute(1.0, 0.0), 0.0);
  EXPECT_EQ(pid.compute(NAN, 0.001), 0.0);
  EXPECT_EQ(pid.compute(1.0, INFINITY, 0.001), 0.0);
}

TEST(Pid, CheckGains) {
  EXPECT_EQ(lcm_control::check_gains(PidGains{1, 0, 0, -1, 1, false}), "");
  EXPECT_NE(lcm_control::check_gains(PidGains{NAN, 0, 0, 0, 0, false}), "");
  EXPECT_NE(lcm_control::check_gains(PidGains{1, 0, 0, 1, 1, false}), "");
}

TEST(Pid, AbsurdGainsGiveAFiniteOutput) {
  Pid pid;
  PidGains g;
  g.p = 1e308;
  g.d = 1e308;
  pid.set_gains(g);
  for (double e : {2.0, -3.0, 5.0}) {
    const double u = pid.compute(e, 1e-3);
    EXPECT_TRUE(std::isfinite(u)) << e;
  }
}

// The gains an output applied, for the damping an effort command declares: none when there was no output.
TEST(Pid, AppliedGainsAreThoseOfTheLastOutputAndZeroWithoutOne) {
  Pid pid(PidGains{600, 0, 30, 0, 0, false});
  EXPECT_EQ(pid.applied_d(), 0.0);
  EXPECT_DOUBLE_EQ(pid.compute(0.1, -2.0, 0.001), 600 * 0.1 - 30 * 2.0);
  EXPECT_EQ(pid.applied_p(), 600.0);
  EXPECT_EQ(pid.applied_d(), 30.0);
  EXPECT_EQ(pid.compute(0.1, -2.0, 0.0), 0.0);  // no period: no output, nothing applied
  EXPECT_EQ(pid.applied_d(), 0.0);
  pid.compute(0.1, -2.0, 0.001);
  EXPECT_EQ(pid.compute(NAN, -2.0, 0.001), 0.0);
  EXPECT_EQ(pid.applied_d(), 0.0);
  pid.compute(0.1, 0.001);
  EXPECT_EQ(pid.applied_p(), 600.0);
  pid.reset();
  EXPECT_EQ(pid.applied_p(), 0.0);
}
