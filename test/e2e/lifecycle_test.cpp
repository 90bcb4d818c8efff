// Hardware components' lifecycle end to end (test/robots/two_component_arm: arm, gripper and wrist IMU as three
// <ros2_control> blocks) in Bullet in real time, through cmctl as a ROS 2 user drives it: set the arm inactive
// mid-motion and its trajectory controller stops while the gripper's runs on, the arm's joints hold; active again and
// a trajectory goal succeeds; a failure injected into the gripper (sim_server's test hook) deactivates exactly the
// controllers using it, logged once with the reason.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <string>

#include "bus/bus.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lcm_control::testing {
namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

size_t count(const std::string& s, const std::string& part) {
  size_t n = 0;
  for (size_t at = s.find(part); at != std::string::npos; at = s.find(part, at + 1)) ++n;
  return n;
}

double position_of(const joint_state_t& m, const std::string& joint) {
  for (int k = 0; k < m.num_joints; ++k)
    if (m.name[size_t(k)] == joint) return m.position[size_t(k)];
  return NAN;
}

class Lifecycle : public ::testing::Test {
 protected:
  void SetUp() override {
    robot.start_controller_manager();
    ASSERT_NO_FATAL_FAILURE(robot.start_sim({}, 20));
    ASSERT_NO_FATAL_FAILURE(
        robot.spawn({"joint_state_broadcaster", "arm_controller", "gripper_controller", "imu_broadcaster"}));
  }
  int cmctl(std::vector<std::string> args, std::string* out) {
    args.insert(args.begin(), "cmctl");
    return robot.run(args, out, 20);
  }
  RobotSession robot{source("test/robots/two_component_arm.urdf"), source("test/robots/two_component_arm.yaml")};
};

TEST_F(Lifecycle, AnInactiveArmStopsItsControllerAndHoldsWhileTheGripperRunsOn) {
  Bus bus(robot.url(), "");
  Recorder<joint_state_t> states(bus.lcm(), "joint_states");
  std::string out;
  ASSERT_EQ(robot.run({"send-trajectory", "arm_controller", "--point", "1:0.4,-0.3", "--no-wait"}, &out), 0) << out;
  pump_until(bus.lcm(), [] { return false; }, 0.5);  // mid-motion
  ASSERT_EQ(cmctl({"set-hardware-component-state", "arm", "inactive"}, &out), 0) << out << robot.cm_output();
  EXPECT_TRUE(has(out, "hardware component 'arm': active -> inactive (deactivate); stopped [arm_controller]")) << out;
  ASSERT_EQ(cmctl({"list"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "hardware components not active: arm (inactive)")) << out;
  ASSERT_EQ(cmctl({"list-hardware-components"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "arm")) << out;
  EXPECT_TRUE(has(out, "inactive")) << out;

  // The arm holds where it was stopped for a second, while the gripper still takes commands.
  pump_until(bus.lcm(), [] { return false; }, 0.2);
  states.messages.clear();
  float64_array_t finger{};
  finger.size = 1;
  finger.data = {0.03};
  bus.lcm().publish("gripper_controller/command", &finger);
  pump_until(bus.lcm(), [] { return false; }, 1.0);
  ASSERT_GT(states.messages.size(), 20u);
  double drift = 0;
  for (const char* j : {"shoulder", "elbow"}) {
    const double first = position_of(states.messages.front(), j);
    for (const auto& m : states.messages) drift = std::max(drift, std::abs(position_of(m, j) - first));
  }
  EXPECT_LT(drift, 1e-3) << "the arm's joints while its component is inactive";
  std::printf("arm inactive: largest drift %.3g rad over %zu joint_states (1 s)\n", drift, states.messages.size());
  const double moved = position_of(states.messages.front(), "shoulder");
  EXPECT_GT(moved, 0.02) << "stopped mid-motion, not before it";
  EXPECT_LT(moved, 0.39) << "stopped mid-motion, not after it";
  EXPECT_NEAR(position_of(states.messages.back(), "finger_joint"), 0.03, 2e-3) << "the gripper is its own component";

  // A goal for a stopped controller is refused; active again, the controller restarts and the goal succeeds.
  ASSERT_EQ(cmctl({"set-hardware-component-state", "arm", "active"}, &out), 0) << out;
  ASSERT_EQ(cmctl({"switch", "--activate", "arm_controller"}, &out), 0) << out;
  ASSERT_EQ(robot.run({"send-trajectory", "arm_controller", "--point", "1:0.4,-0.3"}, &out), 0) << out;
  pump_until(bus.lcm(), [] { return false; }, 0.3);
  EXPECT_NEAR(position_of(states.messages.back(), "shoulder"), 0.4, 0.02);
}

TEST_F(Lifecycle, AFailedGripperDeactivatesExactlyTheControllersUsingItAndSaysSoOnce) {
  std::string out;
  ASSERT_EQ(cmctl({"fail-hardware-component", "gripper", "--reason", "finger motor over current"}, &out), 0)
      << out << robot.sim_output();
  Bus bus(robot.url(), "");
  ASSERT_TRUE(pump_until(bus.lcm(), [&] { return has(robot.cm_output(), "hardware component 'gripper' failed"); }, 5))
      << robot.cm_output();
  pump_until(bus.lcm(), [] { return false; }, 0.5);
  const std::string log = robot.cm_output();
  EXPECT_EQ(count(log, "hardware component 'gripper' failed"), 1u) << log;
  EXPECT_TRUE(has(log, "finger motor over current; deactivated the controllers using it [joint_state_broadcaster, "
                       "gripper_controller]"))
      << log;
  ASSERT_EQ(cmctl({"list"}, &out), 0) << out;
  for (const char* running : {"arm_controller", "imu_broadcaster"}) {
    const size_t line = out.find(running);
    ASSERT_NE(line, std::string::npos) << out;
    EXPECT_TRUE(has(out.substr(line, out.find('\n', line) - line), "active")) << out;
  }
  EXPECT_TRUE(has(out, "hardware components not active: gripper (unconfigured")) << out;
  ASSERT_EQ(cmctl({"list-hardware-components"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "finger motor over current")) << out;
  EXPECT_TRUE(has(robot.sim_output(), "hardware component 'gripper': the controller manager took its error"))
      << robot.sim_output();
  // Fixed and activated again, its controllers start.
  ASSERT_EQ(cmctl({"set-hardware-component-state", "gripper", "active"}, &out), 0) << out;
  ASSERT_EQ(cmctl({"switch", "--activate", "gripper_controller", "joint_state_broadcaster"}, &out), 0) << out;
}

}  // namespace
}  // namespace lcm_control::testing
