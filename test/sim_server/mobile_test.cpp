// A floating base on the ground: diff_bot rests on its wheels and caster,
// rolls straight with equal wheel speeds (distance = speed x radius x time),
// turns in place with opposite ones, and a reset puts it back at the start.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

RobotModel diff_bot() { return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/config/diff_bot.urdf", ""); }

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

}  // namespace
}  // namespace lcm_control::sim
