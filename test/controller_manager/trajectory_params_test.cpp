// ros_controllers' JointTrajectoryController parameters beyond the tutorial
// (state_publish_rate, stop_trajectory_duration, allow_partial_joints_goal,
// velocity_ff on the velocity interface) and
// effort_controllers/JointGroupPositionController, on the simulated rig.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/joint_trajectory_controller_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using lcm_control::testing::Recorder;
using lcm_control::testing::Rig;
using lcm_control::testing::trajectory_goal;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }



// Largest |position error| of a velocity JointTrajectoryController moving the wheel 3 rad in 2 s.
double wheel_tracking_error(const std::string& controller) {
  Rig rig;
  rig.actuator("wheel_motor").inertia = 0.05;
  Recorder<joint_trajectory_controller_state_t> state(rig.bus.lcm(), controller + "/state");
  rig.start(controller);
  rig.publish(controller + "/command", trajectory_goal(1, {"wheel"}, {{2.0, {3.0}}}));
  rig.cycle(2500);
  double worst = 0;
  for (const auto& s : state.messages) worst = std::max(worst, std::abs(s.error_position[0]));
  return worst;
}

}  // namespace

TEST(ControllerManagerTrajectoryParams, StateIsPublishedAtStatePublishRateAndNeverAtZero) {
  Rig rig;
  Recorder<joint_trajectory_controller_state_t> state(rig.bus.lcm(), "trajectory_state/state");
  Recorder<joint_trajectory_controller_state_t> quiet(rig.bus.lcm(), "trajectory_quiet/state");
  rig.start("trajectory_state");
  rig.publish("trajectory_state/command", trajectory_goal(1, {"slide", "tilt"}, {{1.0, {0.5, 0.2}}}));
  rig.cycle(1000);
  EXPECT_NEAR(static_cast<double>(state.messages.size()), 50.0, 1.0);
  ASSERT_FALSE(state.messages.empty());
  const auto& s = state.messages[state.messages.size() / 2];
  EXPECT_EQ(s.joint_names, (std::vector<std::string>{"slide", "tilt"}));
  for (int k = 0; k < 2; ++k)
    EXPECT_NEAR(s.error_position[k], s.desired_position[k] - s.actual_position[k], 1e-12) << k;
  EXPECT_GT(s.desired_velocity[0], 0.0);  // mid-trajectory

  ASSERT_TRUE(rig.load("trajectory_quiet").ok);
  ASSERT_TRUE(rig.switch_({"trajectory_quiet"}, {"trajectory_state"}).ok);
  rig.cycle(500);
  EXPECT_TRUE(quiet.messages.empty());
}

TEST(ControllerManagerTrajectoryParams, AnEmptyTrajectoryStopsWithinStopTrajectoryDuration) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "trajectory_state/result");
  Recorder<joint_trajectory_controller_state_t> state(rig.bus.lcm(), "trajectory_state/state");
  rig.start("trajectory_state");
  rig.publish("trajectory_state/command", trajectory_goal(1, {"slide", "tilt"}, {{2.0, {1.0, 0.0}}}));
  rig.cycle(1000);
  const double at_stop = rig.actuator("slide_motor").position;
  const double speed = state.messages.back().desired_velocity[0];
  ASSERT_GT(speed, 0.3);
  rig.publish("trajectory_state/command", trajectory_goal(2, {"slide", "tilt"}, {}));
  ASSERT_EQ(result.messages.size(), 2u);
  EXPECT_EQ(result.messages[0].goal_id, 1);
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::PREEMPTED) << result.messages[0].message;
  EXPECT_EQ(result.messages[1].goal_id, 2);
  EXPECT_EQ(result.messages[1].status, trajectory_status_t::SUCCEEDED) << result.messages[1].message;
  EXPECT_TRUE(has(result.messages[1].message, "empty trajectory, stopping (over 0.2 s)")) << result.messages[1].message;
  rig.cycle(200);  // the ramp
  const double stopped = rig.actuator("slide_motor").position;
  rig.cycle(300);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, stopped);  // at rest once the ramp is over
  // ros_controllers' ramp: the midpoint of the quintic from (p, v) to (p, -v) over twice the duration, where the
  // velocity is 0: p + 0.625 * v * T with zero accelerations.
  EXPECT_NEAR(stopped - at_stop, 0.625 * speed * 0.2, 0.005);
  EXPECT_LT(stopped, 0.9);  // far from the cancelled goal
}

TEST(ControllerManagerTrajectoryParams, APartialGoalMovesItsJointsAndTheOthersHold) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "trajectory_partial/result");
  rig.start("trajectory_partial");
  const double tilt = rig.actuator("tilt_motor").position;
  rig.publish("trajectory_partial/command", trajectory_goal(1, {"slide"}, {{1.0, {0.7}}}));
  rig.cycle(1700);
  ASSERT_EQ(result.messages.size(), 1u);
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::SUCCEEDED) << result.messages[0].message;
  EXPECT_NEAR(rig.actuator("slide_motor").position, 0.7, 1e-9);
  EXPECT_DOUBLE_EQ(rig.actuator("tilt_motor").position, tilt);
}

TEST(ControllerManagerTrajectoryParams, VelocityFeedForwardCutsTheTrackingErrorOfTheVelocityInterface) {
  const double with_ff = wheel_tracking_error("velocity_trajectory_ff");
  const double without = wheel_tracking_error("velocity_trajectory_no_ff");
  std::printf("velocity JTC, wheel 3 rad in 2 s: largest error %.4f rad with velocity_ff 1, %.4f without\n", with_ff,
              without);
  EXPECT_GT(without, 0.02);  // p alone lags by about v/p
  EXPECT_LT(with_ff, 0.3 * without);
}

TEST(ControllerManagerGroupEffortPosition, EveryJointReachesItsSetPointAgainstGravity) {
  Rig rig;
  auto& arm = rig.actuator("arm_motor");
  arm.gravity = 10.0;
  arm.inertia = 0.2;
  rig.actuator("spin_motor").inertia = 0.1;
  rig.start("group_effort_position");
  float64_array_t cmd{};
  cmd.size = 2;
  cmd.data = {0.6, 1.5};
  rig.publish("group_effort_position/command", cmd);
  rig.cycle(4000);
  EXPECT_NEAR(rig.actuator("arm_motor").position, 0.6, 0.01);
  EXPECT_NEAR(rig.actuator("spin_motor").position, 1.5, 0.01);

  cmd.size = 1;  // one value for two joints: dropped, the set points stay
  cmd.data = {0.0};
  rig.publish("group_effort_position/command", cmd);
  rig.cycle(1000);
  EXPECT_NEAR(rig.actuator("arm_motor").position, 0.6, 0.01);
}

TEST(ControllerManagerGroupEffortPosition, AJointWithoutItsPidIsRefusedNamingIt) {
  Rig rig;
  rig.cycle();
  const cm::Reply r = rig.load("group_effort_position_no_pid");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "spin")) << r.message;
  EXPECT_TRUE(has(r.message, "spin: {pid: {p: ..., i: ..., d: ...}}")) << r.message;
}

// A misspelt ROS 2 key is named with the one meant, and a list that is not of joints is not called one.
TEST(ControllerManagerTrajectoryParams, AMisspeltRequiredKeyIsNamedWithTheOneMeant) {
  const std::string dir = lcm_control::testing::temp_dir("misspelt_key");
  const std::string yaml = dir + "/jtc.yaml";
  std::ofstream(yaml) << "controller_manager:\n  ros__parameters:\n    update_rate: 1000\n"
                         "    arm: {type: joint_trajectory_controller/JointTrajectoryController}\n"
                         "arm:\n  ros__parameters:\n    joints: [slide, tilt]\n    command_interface: [position]\n"
                         "    state_interfaces: [position, velocity]\n";
  Rig rig(lcm_control::cm::builtin_registry(), lcm_control::testing::data("test_bot.urdf"), yaml);
  const auto r = rig.load("arm");
  ASSERT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "arm/command_interfaces: missing (required): a list of names; the file has "
                             "'command_interface': did you mean 'command_interfaces'?"))
      << r.message;
}
