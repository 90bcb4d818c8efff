// Mimic joints in Bullet: the gripper's right finger follows the left one
// through a gear constraint with the URDF's multiplier and offset, starts where
// the left one puts it, and, closing on a box, both fingers stop at the box
// with the mimic carrying its share of the grip.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

RobotModel gripper() {
  return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/gripper.urdf",
                          std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/gripper.yaml");
}

struct Gripper {
  explicit Gripper(const RobotModel& m, const InitialPositions& start = {}) : sim(m, {}, start) {}
  Simulation sim;
  int finger = sim.actuators().find_joint("left_finger_joint");
  int right = sim.multibody().joint_index("right_finger_joint");
  double left_q() { return sim.actuators().joint_position(finger); }
  double right_q() { return sim.multibody().position(sim.multibody().joints()[right].link); }
  void close_to(double q, int steps) {
    run(sim, steps, [&](int) { sim.actuators().set_command(finger, kPos, q); });
  }
};

TEST(sim_mimic, TheMimicJointHasNoActuatorAndFollowsItsJoint) {
  Gripper g(gripper());
  EXPECT_EQ(g.sim.actuators().size(), 1);
  EXPECT_EQ(g.sim.actuators().find_joint("right_finger_joint"), -1);
  g.close_to(0.02, 1500);
  EXPECT_NEAR(g.left_q(), 0.02, 5e-4);
  EXPECT_NEAR(g.right_q(), g.left_q(), 1e-5);
}

TEST(sim_mimic, MultiplierAndOffsetAndTheStartComeFromTheUrdf) {
  RobotModel m = gripper();
  for (auto& j : m.joints)
    if (j.name == "right_finger_joint") j.mimic->multiplier = 0.5, j.mimic->offset = 0.01;
  Gripper g(m, {{"left_finger_joint", 0.01}});
  EXPECT_DOUBLE_EQ(g.right_q(), 0.5 * 0.01 + 0.01);  // starts where the gear puts it
  g.close_to(0.03, 1500);
  EXPECT_NEAR(g.left_q(), 0.03, 5e-4);
  EXPECT_NEAR(g.right_q(), 0.5 * g.left_q() + 0.01, 1e-5);
}

TEST(sim_mimic, BothFingersStopAtTheBoxAndTheMimicCarriesLoad) {
  Gripper g(gripper());
  g.close_to(0.05, 3000);  // past the box: the PID pushes with p * 0.015 m = 30 N
  // Each finger's inner face meets the box's side at 0.06 - 0.005 - 0.02 = 0.035 m of travel.
  std::printf("left %.5f m, right %.5f m, finger motor %.2f N, gear on the right finger %.2f N\n", g.left_q(),
              g.right_q(), g.sim.actuators().joint_effort(g.finger), g.sim.multibody().mimic_effort(g.right));
  EXPECT_NEAR(g.left_q(), 0.035, 2e-3);
  EXPECT_NEAR(g.right_q(), 0.035, 2e-3);
  EXPECT_NEAR(g.right_q(), g.left_q(), 1e-4);
  EXPECT_NEAR(std::abs(g.sim.actuators().joint_effort(g.finger)), 30.0, 1.0);  // held off by the box
  EXPECT_GT(std::abs(g.sim.multibody().mimic_effort(g.right)), 5.0);           // the right finger grips too
}

TEST(sim_mimic, WithoutSelfCollisionTheFingersPassThroughTheBox) {
  RobotModel m = gripper();
  m.self_collide = false;
  Gripper g(m);
  g.close_to(0.05, 3000);
  EXPECT_NEAR(g.left_q(), 0.05, 1e-3);
  EXPECT_NEAR(g.right_q(), 0.05, 1e-3);
}

}  // namespace
}  // namespace lcm_control::sim
