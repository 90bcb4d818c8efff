#include "controllers/trajectory.hpp"

#include <gtest/gtest.h>

using namespace lcm_control::cm;

namespace {
SplineState at(const Trajectory& t, double time, size_t j = 0) {
  SplineState s;
  t.sample(time, j, s);
  return s;
}
}  // namespace

TEST(ControllerManagerTrajectory, CubicPassesWaypointsWithTheirVelocities) {
  Waypoint a{1.0, {1.0}, {0.5}, {}}, b{2.0, {0.0}, {0.0}, {}};
  const auto t = Trajectory::build(0.0, {SplineState{0, 0, 0}}, {a, b});
  EXPECT_NEAR(at(t, 0.0).pos, 0.0, 1e-12);
  EXPECT_NEAR(at(t, 1.0).pos, 1.0, 1e-12);
  EXPECT_NEAR(at(t, 1.0).vel, 0.5, 1e-12);
  EXPECT_NEAR(at(t, 2.0).pos, 0.0, 1e-12);
  EXPECT_NEAR(at(t, 3.0).pos, 0.0, 1e-12);
  EXPECT_EQ(at(t, 3.0).vel, 0.0);
  EXPECT_DOUBLE_EQ(t.end_time(), 2.0);
}

TEST(ControllerManagerTrajectory, PositionsOnlyIsMonotoneBetweenMonotoneWaypoints) {
  std::vector<Waypoint> w{{1.0, {0.2}, {}, {}}, {1.5, {0.9}, {}, {}}, {3.0, {1.0}, {}, {}}};
  const auto t = Trajectory::build(0.0, {SplineState{0, 0, 0}}, w);
  double prev = -1;
  for (double x = 0; x <= 3.0; x += 0.001) {
    const double p = at(t, x).pos;
    EXPECT_GE(p, prev - 1e-12) << x;
    EXPECT_LE(p, 1.0 + 1e-12) << x;
    prev = p;
  }
  EXPECT_NEAR(at(t, 1.5).pos, 0.9, 1e-12);
  EXPECT_NEAR(at(t, 3.0).vel, 0.0, 1e-9);
}

TEST(ControllerManagerTrajectory, QuinticMatchesPositionVelocityAndAcceleration) {
  Waypoint a{2.0, {1.0}, {0.3}, {-0.2}};
  const auto t = Trajectory::build(1.0, {SplineState{0.5, 0.1, 0.4}}, {a});
  const auto s0 = at(t, 1.0), s1 = at(t, 2.0 - 1e-9);
  EXPECT_NEAR(s0.pos, 0.5, 1e-9);
  EXPECT_NEAR(s0.vel, 0.1, 1e-9);
  EXPECT_NEAR(s0.acc, 0.4, 1e-9);
  EXPECT_NEAR(s1.pos, 1.0, 1e-6);
  EXPECT_NEAR(s1.vel, 0.3, 1e-6);
  EXPECT_NEAR(s1.acc, -0.2, 1e-6);
}

TEST(ControllerManagerTrajectory, HoldStaysPut) {
  auto t = Trajectory::hold(5.0, {1.0, -2.0});
  EXPECT_EQ(at(t, 7.0, 1).pos, -2.0);
  const double p[] = {3.0, 4.0};
  t.set_hold(8.0, p);
  EXPECT_EQ(at(t, 9.0, 0).pos, 3.0);
  EXPECT_EQ(at(t, 9.0, 1).vel, 0.0);
}
