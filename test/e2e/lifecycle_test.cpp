// Hardware components' lifecycle end to end (test/robots/two_component_arm: arm, gripper and wrist IMU as three
// <ros2_control> blocks) in Bullet in real time, through cmctl as a ROS 2 user drives it: set the arm inactive
// mid-motion and its trajectory controller stops while the gripper's runs on, the arm's joints hold; active again and
// a trajectory goal succeeds; a failure injected into the gripper (sim_server's test hook) deactivates exactly the
// controllers using it, logged once with the reason. Controllers with is_async run in lockstep bit for bit twice, and
// as they do in the loop.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#include "bus/bus.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
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

// ROS 2's per-component statistics: sim_server times each hardware component's share of every step (its actuators'
// commands applied and states read back) and reports it with the period between its steps; a component of sensors
// only (the wrist) has no actuators to time.
TEST_F(Lifecycle, StatisticsNameEveryComponentWithActuatorsWithItsShareOfTheStep) {
  Bus bus(robot.url(), "");
  Recorder<loop_stats_t> stats(bus.lcm(), "sim_server/statistics");
  ASSERT_TRUE(pump_until(bus.lcm(), [&] { return stats.messages.size() >= 2; }, 5)) << robot.sim_output();
  const loop_stats_t& s = stats.messages.back();
  auto item = [&](const std::string& name) {
    for (int k = 0; k < s.num_items; ++k)
      if (s.item[size_t(k)] == name) return k;
    return -1;
  };
  const int step = item("step"), arm = item("arm"), gripper = item("gripper");
  ASSERT_GE(step, 0);
  ASSERT_GE(arm, 0);
  ASSERT_GE(gripper, 0);
  EXPECT_EQ(item("wrist"), -1) << "sensors only";
  for (const int c : {arm, gripper}) {
    EXPECT_EQ(s.item_kind[size_t(c)], "component");
    EXPECT_NEAR(double(s.item_count[size_t(c)]), double(s.item_count[size_t(step)]), 1.0);
    EXPECT_GT(s.item_exec_mean_us[size_t(c)], 0.0);
    EXPECT_LT(s.item_exec_mean_us[size_t(c)], s.item_exec_mean_us[size_t(step)]) << "a share of the step";
    EXPECT_NEAR(s.item_period_mean_us[size_t(c)], 2000.0, 200.0) << "update_rate 500";
  }
  std::printf("components: arm %.2f us, gripper %.2f us of a %.2f us step; period %.1f us\n",
              s.item_exec_mean_us[size_t(arm)], s.item_exec_mean_us[size_t(gripper)],
              s.item_exec_mean_us[size_t(step)], s.item_period_mean_us[size_t(arm)]);
  std::string out;
  ASSERT_EQ(cmctl({"statistics"}, &out), 0) << out;
  EXPECT_TRUE(has(out, "component")) << out;
}

// two_component_arm in lockstep for 2 s of sim time, the gripper commanded by a 60 Hz source, its trajectory and
// gripper controllers in the loop or (async) on threads of their own: the joint_states.
std::vector<joint_state_t> lockstep_run(bool async) {
  std::ifstream in(source("test/robots/two_component_arm.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  if (async)
    for (const std::string c : {"arm_controller", "gripper_controller"}) {
      const std::string head = "\n" + c + ":\n  ros__parameters:\n";
      const size_t at = yaml.find(head);
      EXPECT_NE(at, std::string::npos) << c;
      if (at != std::string::npos) yaml.insert(at + head.size(), "    is_async: true\n");
    }
  const std::string dir = temp_dir(async ? "async_lockstep" : "sync_lockstep");
  std::ofstream(dir + "/arm.yaml") << yaml;
  std::ofstream(dir + "/run.launch.yaml")
      << "urdf: " << source("test/robots/two_component_arm.urdf") << "\nconfig: " << dir << "/arm.yaml\n"
      << "mode: lockstep\ncontrollers: [joint_state_broadcaster, arm_controller, gripper_controller]\n"
         "commands:\n  - {target: gripper_controller, expr: [\"0.01*sin(i/20)\"], rate: 60}\n";
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<joint_state_t> states(lc, "joint_states");
  ChildProcess launch({bin("launch"), dir + "/run.launch.yaml", "--duration", "2", "--lcm-url", url});
  while (launch.running()) lc.handleTimeout(20);
  pump_until(lc, [] { return false; }, 0.2);
  EXPECT_EQ(launch.wait(60), 0) << launch.output();
  return states.messages;
}

// ROS 2's is_async in lockstep: the controllers run in the cycle they are due, so two runs are bit-identical, and
// identical to the same controllers in the loop.
TEST(AsyncControllers, InLockstepTwoRunsAreBitIdenticalAndEqualTheLoop) {
  const auto first = lockstep_run(true);
  const auto second = lockstep_run(true);
  const auto in_loop = lockstep_run(false);
  ASSERT_GE(first.size(), 400u);
  ASSERT_EQ(second.size(), first.size());
  ASSERT_EQ(in_loop.size(), first.size());
  double moved = 0;
  for (size_t k = 0; k < first.size(); ++k) {
    ASSERT_EQ(first[k].utime, second[k].utime) << k;
    ASSERT_EQ(first[k].position, second[k].position) << "t=" << first[k].utime * 1e-6;
    ASSERT_EQ(first[k].velocity, second[k].velocity) << "t=" << first[k].utime * 1e-6;
    ASSERT_EQ(first[k].position, in_loop[k].position) << "t=" << first[k].utime * 1e-6;
    moved = std::max(moved, std::abs(position_of(first[k], "finger_joint") - position_of(first[0], "finger_joint")));
  }
  EXPECT_GT(moved, 0.005) << "the gripper followed its command source";
  std::printf("async lockstep: %zu joint_states bit-identical in two runs and to the loop; finger moved %.4f m\n",
              first.size(), moved);
}

}  // namespace
}  // namespace lcm_control::testing
