// Run-time switching of a <ros2_control> joint's command interface in the
// Bullet actuators: a command in any offered interface switches the actuator
// at that step without a jump, a mode not offered holds and is counted, and a
// ROS 1 transmission keeps taking only its first interface.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

RobotModel switch_arm() {
  return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/switch_arm.urdf", "");
}

TEST(ModeSwitching, VelocityCommandOnAPositionFirstJointDrivesItInVelocityThenPositionTakesOverWithoutAJump) {
  Simulation sim(switch_arm(), {});
  Actuators& act = sim.actuators();
  const int j1 = act.find_joint("j1");
  ASSERT_GE(j1, 0);
  EXPECT_EQ(act.wire_mode(j1), kPos);
  EXPECT_EQ(act.mode(j1), ActuatorMode::PositionDirect);
  EXPECT_TRUE(act.offers(j1, kVel));
  EXPECT_FALSE(act.offers(j1, kEff));

  run(sim, 1000, [&](int) { ASSERT_TRUE(act.set_command(j1, kVel, 0.5)); });
  EXPECT_EQ(act.wire_mode(j1), kVel);
  EXPECT_EQ(act.mode(j1), ActuatorMode::VelocityMotor);
  EXPECT_NEAR(act.velocity(j1), 0.5, 1e-6);
  EXPECT_NEAR(act.position(j1), 0.5, 2e-3);  // 1 s at 0.5 rad/s

  const double before = act.position(j1);
  ASSERT_TRUE(act.set_command(j1, kPos, 1.5));
  sim.step();
  EXPECT_EQ(act.wire_mode(j1), kPos);
  EXPECT_EQ(act.mode(j1), ActuatorMode::PositionDirect);
  // From where it was, at most the velocity limit (2 rad/s) for one 1 ms step: no jump to the goal.
  EXPECT_LE(std::abs(act.position(j1) - before), 2 * 1e-3 + 1e-9);
  run(sim, 1000, [&](int) { act.set_command(j1, kPos, 1.5); });
  EXPECT_NEAR(act.position(j1), 1.5, 1e-6);
  EXPECT_NEAR(act.velocity(j1), 0.0, 1e-6);
}

TEST(ModeSwitching, APositionCommandHoldsWhereTheVelocityModeLeftTheJoint) {
  Simulation sim(switch_arm(), {});
  Actuators& act = sim.actuators();
  const int j2 = act.find_joint("j2");
  run(sim, 300, [&](int) { act.set_command(j2, kVel, -1.0); });
  run(sim, 1, [&](int) { act.set_command(j2, kPos, act.position(j2)); });
  const double held = act.position(j2);
  run(sim, 500, [&](int) { act.set_command(j2, kPos, held); });
  EXPECT_NEAR(act.position(j2), held, 1e-6);  // the velocity motor left the world: nothing drags it on
}

TEST(ModeSwitching, AModeTheJointDoesNotOfferHoldsAndIsCounted) {
  Simulation sim(switch_arm(), {});
  Actuators& act = sim.actuators();
  const int j1 = act.find_joint("j1");
  run(sim, 200, [&](int) { act.set_command(j1, kPos, 0.2); });
  const double at = act.position(j1);
  run(sim, 100, [&](int) { EXPECT_FALSE(act.set_command(j1, kEff, 40.0)); });
  EXPECT_EQ(act.rejected(j1), 100);
  EXPECT_EQ(act.wire_mode(j1), kPos);
  EXPECT_NEAR(act.position(j1), at, 1e-9);
}

TEST(ModeSwitching, PidGainsGiveThePidVariantOfEachModeStartedAfresh) {
  RobotModel m = switch_arm();
  PidGains g;  // one PID per joint, as gazebo_ros_control: gains that suit both its velocity and its position use
  g.p = 1;
  g.i = 1;
  g.i_clamp_min = -1;
  g.i_clamp_max = 1;
  m.pid_gains["j1"] = g;
  for (Joint& j : m.joints)
    if (j.name == "j1") j.damping = 0.05;
  Simulation sim(m, {});
  Actuators& act = sim.actuators();
  const int j1 = act.find_joint("j1");
  EXPECT_EQ(act.mode(j1), ActuatorMode::PositionPid);
  run(sim, 2000, [&](int) { act.set_command(j1, kVel, 0.4); });
  EXPECT_EQ(act.mode(j1), ActuatorMode::VelocityPid);
  EXPECT_NEAR(act.velocity(j1), 0.4, 0.02);
  const double before = act.position(j1);
  run(sim, 1, [&](int) { act.set_command(j1, kPos, before + 0.3); });
  EXPECT_EQ(act.mode(j1), ActuatorMode::PositionPid);
  EXPECT_LT(std::abs(act.position(j1) - before), 2e-3);
  run(sim, 3000, [&](int) { act.set_command(j1, kPos, before + 0.3); });
  EXPECT_NEAR(act.position(j1), before + 0.3, 5e-3);
}

TEST(ModeSwitching, ARos1TransmissionTakesOnlyItsFirstInterface) {
  RobotModel m = switch_arm();
  for (TransmissionSpec& t : m.transmissions) t.any_interface = false;
  Simulation sim(m, {});
  Actuators& act = sim.actuators();
  EXPECT_TRUE(act.offers(0, kPos));
  EXPECT_FALSE(act.offers(0, kVel));
  EXPECT_FALSE(act.set_command(0, kVel, 0.5));
  EXPECT_EQ(act.wire_mode(0), kPos);
}

TEST(ModeSwitching, TheDescriptionNamesTheModesItSwitchesTo) {
  Simulation sim(switch_arm(), {});
  EXPECT_NE(sim.actuators().describe(0).find("switches on command to velocity (velocity motor)"), std::string::npos)
      << sim.actuators().describe(0);
}

}  // namespace
}  // namespace lcm_control::sim
