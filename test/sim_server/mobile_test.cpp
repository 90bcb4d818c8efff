// A floating base on the ground: diff_bot rests on its wheels and caster,
// rolls straight with equal wheel speeds (distance = speed x radius x time),
// turns in place with opposite ones, and a reset puts it back at the start.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

RobotModel diff_bot() { return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/config/diff_bot.urdf", ""); }
RobotModel four_wheel_base() {
  return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/four_wheel_base.urdf", "");
}

struct DiffBot {
  DiffBot() : sim(diff_bot(), {}, {}, WorldOptions{true, true}) {}
  Simulation sim;
  void drive(double left, double right, int steps) {
    run(sim, steps, [&](int) {
      Actuators& a = sim.actuators();
      a.set_command(a.find_joint("wheel_left_joint"), kVel, left);
      a.set_command(a.find_joint("wheel_right_joint"), kVel, right);
    });
  }
  Eigen::Isometry3d pose() { return sim.multibody().base_pose(); }
  double yaw() { return std::atan2(pose().linear()(1, 0), pose().linear()(0, 0)); }
};

TEST(sim_mobile, RestsOnTheGroundUpright) {
  DiffBot b;
  b.drive(0, 0, 1000);
  std::printf("at rest: z %.5f m, x %.5f, y %.5f, tilt %.5f rad\n", b.pose().translation().z(), b.pose().translation().x(),
              b.pose().translation().y(), std::acos(b.pose().linear()(2, 2)));
  EXPECT_NEAR(b.pose().translation().z(), 0.0, 2e-3);
  EXPECT_NEAR(b.pose().translation().x(), 0.0, 1e-3);
  EXPECT_LT(std::acos(std::min(1.0, b.pose().linear()(2, 2))), 0.02);
}

TEST(sim_mobile, EqualWheelSpeedsRollStraight) {
  DiffBot b;
  b.drive(0, 0, 200);
  b.drive(5, 5, 2000);  // 5 rad/s x 0.033 m = 0.165 m/s for 2 s
  std::printf("straight: x %.4f m, y %.4f m, yaw %.4f rad, v %.4f m/s\n", b.pose().translation().x(),
              b.pose().translation().y(), b.yaw(), b.sim.multibody().base_linear_velocity().x());
  EXPECT_NEAR(b.pose().translation().x(), 0.33, 0.02);
  EXPECT_NEAR(b.pose().translation().y(), 0.0, 0.005);
  EXPECT_NEAR(b.yaw(), 0.0, 0.02);
}

TEST(sim_mobile, OppositeWheelSpeedsTurnInPlace) {
  DiffBot b;
  b.drive(0, 0, 200);
  b.drive(-2, 2, 2000);  // yaw rate = 2 x 2 x 0.033 / 0.16 = 0.825 rad/s for 2 s
  std::printf("turn: yaw %.4f rad, x %.4f, y %.4f\n", b.yaw(), b.pose().translation().x(), b.pose().translation().y());
  EXPECT_NEAR(b.yaw(), 1.65, 0.08);
  EXPECT_NEAR(b.pose().translation().norm(), 0.0, 0.03);
}

TEST(sim_mobile, AResetPutsTheBaseBackAtItsStart) {
  DiffBot b;
  b.drive(5, 5, 1000);
  b.sim.reset();
  EXPECT_NEAR(b.pose().translation().norm(), 0.0, 1e-9);
}

// A base whose root frame is on the wheel axles, spawned at z = 0: the wheels would start 5 cm inside the ground and
// Bullet's penetration recovery would throw it up (30+ m for a heavier base). It starts lifted onto its wheels.
TEST(sim_mobile, ABaseSpawnedInsideTheGroundStartsRestingOnIt) {
  const RobotModel model = four_wheel_base();
  auto settle = [&](double* max_z) {
    auto sim = std::make_unique<Simulation>(model, SimulationRates{}, InitialPositions{}, WorldOptions{true, true});
    *max_z = -1;
    run(*sim, 3000, [&](int) { *max_z = std::max(*max_z, sim->multibody().base_pose().translation().z()); });
    return sim;
  };
  double max_z = 0;
  auto sim = settle(&max_z);
  ASSERT_EQ(sim->notes().size(), 1u);
  EXPECT_THAT(sim->notes()[0], ::testing::HasSubstr("robot 'four_wheel_base'"));
  EXPECT_THAT(sim->notes()[0], ::testing::HasSubstr("lifted by 0.05 m"));
  const double z = sim->multibody().base_pose().translation().z();
  const double v = sim->multibody().base_linear_velocity().norm();
  std::printf("four_wheel_base from z = 0: max z %.5f m in 3 s, at rest z %.5f m, |v| %.2e m/s\n", max_z, z, v);
  EXPECT_NEAR(z, 0.05, 2e-3);   // on its wheels (radius 0.05)
  EXPECT_LT(max_z, 0.05 + 0.02);  // never thrown
  EXPECT_LT(v, 1e-3);
  double max_again = 0;  // the lift is part of the deterministic start
  auto again = settle(&max_again);
  EXPECT_EQ(max_again, max_z);
  EXPECT_EQ(again->multibody().base_pose().translation().z(), z);
}

TEST(sim_mobile, ABaseAboveTheGroundIsNotMoved) {
  WorldOptions world{true, true};
  world.base_position = {0, 0, 0.2};
  Simulation sim(four_wheel_base(), {}, {}, world);
  EXPECT_TRUE(sim.notes().empty());
  EXPECT_NEAR(sim.multibody().base_pose().translation().z(), 0.2, 1e-12);
}

}  // namespace
}  // namespace lcm_control::sim
