// Mock hardware (mock_components/GenericSystem's semantics) on the project's
// mock_arm: state follows command, position_state_following_offset,
// calculate_dynamics, mimic joints, initial_value, hold, modes not offered;
// and the Simulation's mock backend with its reset.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/mock_hardware.hpp"
#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

constexpr double kDt = 0.001;

RobotModel robot(const std::string& file) {
  return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/" + file, "");
}

// mock_arm.urdf with its hardware <param>s replaced.
RobotModel mock_arm(const Ros2Params& params) {
  RobotModel m = robot("mock_arm.urdf");
  m.ros2_control.at(0).params = params;
  return m;
}

TEST(MockHardware, ChosenWhenEveryBlockNamesMockHardware) {
  EXPECT_TRUE(all_mock_hardware(robot("mock_arm.urdf")));
  EXPECT_FALSE(all_mock_hardware(robot("switch_arm.urdf")));
  EXPECT_FALSE(all_mock_hardware(turret()));  // no <ros2_control> block
}

TEST(MockHardware, PositionCommandIsTheStateExactlyAndTheMimicFollows) {
  const RobotModel m = mock_arm({});
  MockHardware hw(m, m.initial_positions);
  EXPECT_EQ(hw.position(0), 0.5);  // initial_value
  EXPECT_EQ(hw.joint_position("j3"), 0.1);  // -2 x 0 + 0.1
  ASSERT_TRUE(hw.set_command(0, kPos, 0.123456789));
  ASSERT_TRUE(hw.set_command(1, kPos, -0.4));
  hw.step(kDt);
  EXPECT_EQ(hw.position(0), 0.123456789);
  EXPECT_EQ(hw.position(1), -0.4);
  EXPECT_EQ(hw.velocity(0), 0.0);  // without calculate_dynamics the velocity is not derived
  EXPECT_DOUBLE_EQ(hw.joint_position("j3"), -2 * -0.4 + 0.1);
}

TEST(MockHardware, FollowingOffsetIsAddedToThePosition) {
  MockHardware hw(mock_arm({{"position_state_following_offset", "0.05"}}), {});
  hw.set_command(0, kPos, 1.0);
  hw.step(kDt);
  EXPECT_DOUBLE_EQ(hw.position(0), 1.05);
}

TEST(MockHardware, CalculateDynamicsDifferentiatesPositionAndIntegratesVelocity) {
  MockHardware hw(mock_arm({{"calculate_dynamics", "true"}}), {});
  hw.set_command(0, kPos, 0.01);
  hw.step(kDt);
  EXPECT_DOUBLE_EQ(hw.velocity(0), 0.01 / kDt);
  // Velocity: the position moves by the previous step's velocity (GenericSystem's backward Euler).
  hw.set_command(1, kVel, 0.5);
  hw.step(kDt);
  EXPECT_EQ(hw.velocity(1), 0.5);
  EXPECT_EQ(hw.position(1), 0.0);
  for (int k = 0; k < 1000; ++k) hw.step(kDt);
  EXPECT_NEAR(hw.position(1), 0.5, 1e-9);
  EXPECT_NEAR(hw.joint_velocity("j3"), -1.0, 1e-12);
  EXPECT_EQ(hw.wire_mode(1), kVel);
}

TEST(MockHardware, VelocityWithoutDynamicsOnlySetsTheVelocity) {
  MockHardware hw(mock_arm({}), {});
  hw.set_command(1, kVel, 0.5);
  for (int k = 0; k < 100; ++k) hw.step(kDt);
  EXPECT_EQ(hw.velocity(1), 0.5);
  EXPECT_EQ(hw.position(1), 0.0);
}

// ros2_control_demos' hardware (a diffbot's, a car's) integrates its wheels' velocity commands: played as mock
// hardware, calculate_dynamics is on unless the block says otherwise.
TEST(MockHardware, ADemoPluginIntegratesVelocityUnlessItsBlockSaysOtherwise) {
  for (const bool said_false : {false, true}) {
    RobotModel m = mock_arm(said_false ? Ros2Params{{"calculate_dynamics", "false"}} : Ros2Params{});
    m.ros2_control.at(0).plugin = "ros2_control_demo_example_2/DiffBotSystemHardware";
    MockHardware hw(m, {});
    hw.set_command(1, kVel, 0.5);
    for (int k = 0; k < 1001; ++k) hw.step(kDt);
    EXPECT_NEAR(hw.position(1), said_false ? 0.0 : 0.5, 1e-9) << (said_false ? "calculate_dynamics false" : "demo");
  }
}

TEST(MockHardware, NobodyCommandingHoldsThePositionAndAModeNotOfferedHoldsToo) {
  MockHardware hw(mock_arm({{"calculate_dynamics", "true"}}), {});
  hw.set_command(0, kVel, 1.0);
  for (int k = 0; k < 100; ++k) hw.step(kDt);
  const double at = hw.position(0);
  hw.set_command(0, kNone, 0);
  hw.step(kDt);
  EXPECT_EQ(hw.position(0), at);
  EXPECT_EQ(hw.velocity(0), 0.0);
  EXPECT_FALSE(hw.set_command(0, kEff, 3.0));  // j1 offers position and velocity
  hw.step(kDt);
  EXPECT_EQ(hw.position(0), at);
  EXPECT_EQ(hw.effort(0), 0.0);
}

TEST(MockHardware, EffortCommandIsTheEffortState) {
  RobotModel m = mock_arm({});
  m.transmissions[0].interfaces.push_back(Interface::Effort);
  MockHardware hw(m, {});
  ASSERT_TRUE(hw.set_command(0, kEff, 3.5));
  hw.step(kDt);
  EXPECT_EQ(hw.effort(0), 3.5);
  EXPECT_EQ(hw.wire_mode(0), kEff);
}

TEST(MockHardware, AStartOutsideTheLimitsIsClampedAndSaid) {
  MockHardware hw(mock_arm({}), {{"j2", 9.0}});
  EXPECT_EQ(hw.position(1), 2.0);
  ASSERT_EQ(hw.start_warnings().size(), 1u);
  EXPECT_NE(hw.start_warnings()[0].find("joint 'j2' would start at 9"), std::string::npos);
  EXPECT_THROW(MockHardware(mock_arm({}), {{"nope", 1.0}}), ModelError);
}

TEST(MockHardware, AnOffsetThatIsNotANumberNamesTheBlock) {
  try {
    MockHardware hw(mock_arm({{"position_state_following_offset", "abc"}}), {});
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("ros2_control 'MockArm': <param name=\"position_state_following_offset\"> "
                                         "'abc' is not a number"),
              std::string::npos)
        << e.what();
  }
}

TEST(MockHardware, SimulationBackendStepsAndResetsWithoutPhysics) {
  const RobotModel m = mock_arm({});
  Simulation sim(m, {}, m.initial_positions, {}, Backend::Mock);
  EXPECT_EQ(sim.backend(), Backend::Mock);
  EXPECT_FALSE(sim.floating_base());
  PlayedHardware& hw = sim.hardware();
  run(sim, 10, [&](int k) { hw.set_command(1, kPos, 0.01 * k); });
  EXPECT_EQ(sim.step_count(), 10);
  EXPECT_DOUBLE_EQ(hw.position(1), 0.09);
  sim.hardware().set_hold_all(true);
  sim.reset({{"j2", -0.3}});
  EXPECT_EQ(sim.step_count(), 0);
  EXPECT_EQ(sim.hardware().position(0), 0.5);
  EXPECT_EQ(sim.hardware().position(1), -0.3);
  EXPECT_TRUE(sim.hardware().hold_all());  // carried over, as the Bullet backend does
}

}  // namespace
}  // namespace lcm_control::sim
