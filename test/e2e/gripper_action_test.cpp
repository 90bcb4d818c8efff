// GripperActionController end to end: sim_server and controller_manager over LCM on the gripper test robot
// (test/robots/gripper.urdf: the right finger mimics the left, a box between them stops both at 0.035), driven by
// the `gripper` tool: a goal to an opening succeeds with both fingers there, a goal past the box stalls and is
// ABORTED (exit 1), or SUCCEEDED with allow_stalling (exit 0); a controller that takes no gripper goals is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "lcm_control/gripper_status_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lcm_control::testing {
namespace {

double at(const joint_state_t& m, const std::string& joint) {
  for (int k = 0; k < m.num_joints; ++k)
    if (m.name[k] == joint) return m.position[k];
  return double(NAN);
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TEST(GripperAction, ClosesToAnOpeningAndStallsOnTheBoxAsAllowStallingSays) {
  const std::string url = unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  const std::string urdf = source("test/robots/gripper.urdf"), yaml = source("test/robots/gripper_action.yaml");
  lcm::LCM lc(url);
  Recorder<joint_state_t> states(lc, "joint_states");
  Recorder<gripper_status_t> results(lc, "gripper_controller/result");
  Recorder<gripper_status_t> grasps(lc, "grasp_controller/result");
  ChildProcess cm({bin("controller_manager"), "--urdf", urdf, "--config", yaml}, env);
  ChildProcess sim({bin("sim_server"), "--urdf", urdf, "--config", yaml}, env);
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "gripper_controller"}, env);
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 30)) << spawner.output() << cm.output() << sim.output();
  // Goals once the hardware ticks (the first hardware session restarts the controllers, preempting a goal).
  ASSERT_TRUE(pump_until(lc, [&] { return states.messages.size() > 5; }, 20)) << cm.output() << sim.output();

  ChildProcess open({bin("gripper"), "gripper_controller", "--position", "0.02", "--timeout", "10"}, env);
  ASSERT_EQ(open.wait(20), 0) << open.output() << cm.output();
  EXPECT_TRUE(has(open.output(), "gripper_controller: SUCCEEDED: goal ")) << open.output();
  EXPECT_TRUE(has(open.output(), "reached goal")) << open.output();
  pump_until(lc, [&] { return results.messages.size() >= 1 && states.messages.size() > 10; }, 5);
  ASSERT_EQ(results.messages.size(), 1u);
  EXPECT_EQ(results.messages[0].status, gripper_status_t::SUCCEEDED) << results.messages[0].message;
  EXPECT_NEAR(results.messages[0].position, 0.02, 0.002);
  const size_t seen = states.messages.size();
  pump_until(lc, [&] { return states.messages.size() > seen + 10; }, 5);
  ASSERT_FALSE(states.messages.empty());
  EXPECT_NEAR(at(states.messages.back(), "left_finger_joint"), 0.02, 0.002);
  EXPECT_NEAR(at(states.messages.back(), "right_finger_joint"), 0.02, 0.002);  // the <mimic> finger

  // Past the box: the fingers stop at 0.035 and the goal, without allow_stalling, is aborted.
  ChildProcess past({bin("gripper"), "gripper_controller", "--position", "0.05", "--timeout", "10"}, env);
  EXPECT_EQ(past.wait(20), 1) << past.output();
  EXPECT_TRUE(has(past.output(), "gripper: error: gripper_controller: ABORTED: stalled at 0.03")) << past.output();
  EXPECT_TRUE(has(past.output(), "stalled)")) << past.output();
  pump_until(lc, [&] { return results.messages.size() >= 2; }, 5);
  ASSERT_EQ(results.messages.size(), 2u);
  EXPECT_EQ(results.messages[1].status, gripper_status_t::ABORTED) << results.messages[1].message;
  EXPECT_TRUE(results.messages[1].stalled);
  EXPECT_NEAR(results.messages[1].position, 0.035, 0.002);

  // The same grasp with allow_stalling (ROS 2's parallel gripper) is a success.
  ChildProcess load({bin("cmctl"), "load", "grasp_controller"}, env);
  ASSERT_EQ(load.wait(20), 0) << load.output();
  ChildProcess sw({bin("cmctl"), "switch", "--start", "grasp_controller", "--stop", "gripper_controller"}, env);
  ASSERT_EQ(sw.wait(20), 0) << sw.output();
  ChildProcess release({bin("gripper"), "grasp_controller", "--position", "0.0"}, env);
  ASSERT_EQ(release.wait(20), 0) << release.output();
  ChildProcess grasp({bin("gripper"), "grasp_controller", "--position", "0.05"}, env);
  ASSERT_EQ(grasp.wait(20), 0) << grasp.output();
  EXPECT_TRUE(has(grasp.output(), "grasp_controller: SUCCEEDED: stalled at 0.03")) << grasp.output();
  EXPECT_TRUE(has(grasp.output(), "allow_stalling: succeeded")) << grasp.output();
  pump_until(lc, [&] { return grasps.messages.size() >= 2; }, 5);
  ASSERT_EQ(grasps.messages.size(), 2u);
  EXPECT_TRUE(grasps.messages[1].stalled);
  EXPECT_FALSE(grasps.messages[1].reached_goal);

  // A controller that takes no gripper goals is named with its type.
  ChildProcess wrong({bin("gripper"), "joint_state_controller", "--position", "0.01"}, env);
  EXPECT_EQ(wrong.wait(20), 1) << wrong.output();
  EXPECT_TRUE(has(wrong.output(), "gripper: error: joint_state_controller "
                                  "(joint_state_controller/JointStateController) takes no commands (it only reads the "
                                  "joints and publishes joint_states); gripper_command_t was given on "
                                  "joint_state_controller/command"))
      << wrong.output();
  ChildProcess stopped({bin("gripper"), "gripper_controller", "--position", "0.01"}, env);
  EXPECT_EQ(stopped.wait(20), 1) << stopped.output();
  EXPECT_TRUE(has(stopped.output(), "'gripper_controller' is loaded but stopped, not running: start it with `cmctl "
                                    "start gripper_controller`"))
      << stopped.output();
}

}  // namespace
}  // namespace lcm_control::testing
