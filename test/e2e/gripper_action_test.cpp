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
#include "test/e2e/session.hpp"
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
  RobotSession robot(source("test/robots/gripper.urdf"), source("test/robots/gripper_action.yaml"));
  lcm::LCM lc(robot.url());
  Recorder<joint_state_t> states(lc, "joint_states");
  Recorder<gripper_status_t> results(lc, "gripper_controller/result");
  Recorder<gripper_status_t> grasps(lc, "grasp_controller/result");
  robot.start_controller_manager();
  robot.start_sim();
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_controller", "gripper_controller"}));
  // Goals once the hardware ticks (the first hardware session restarts the controllers, preempting a goal).
  ASSERT_TRUE(pump_until(lc, [&] { return states.messages.size() > 5; }, 20)) << robot.cm_output() << robot.sim_output();

  std::string open_out;
  const int open_rc = robot.run({"gripper", "gripper_controller", "--position", "0.02", "--timeout", "10"}, &open_out, 20);
  ASSERT_EQ(open_rc, 0) << open_out << robot.cm_output();
  EXPECT_TRUE(has(open_out, "gripper_controller: SUCCEEDED: goal ")) << open_out;
  EXPECT_TRUE(has(open_out, "reached goal")) << open_out;
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
  std::string past_out;
  const int past_rc = robot.run({"gripper", "gripper_controller", "--position", "0.05", "--timeout", "10"}, &past_out, 20);
  EXPECT_EQ(past_rc, 1) << past_out;
  EXPECT_TRUE(has(past_out, "gripper: error: gripper_controller: ABORTED: stalled at 0.03")) << past_out;
  EXPECT_TRUE(has(past_out, "stalled)")) << past_out;
  pump_until(lc, [&] { return results.messages.size() >= 2; }, 5);
  ASSERT_EQ(results.messages.size(), 2u);
  EXPECT_EQ(results.messages[1].status, gripper_status_t::ABORTED) << results.messages[1].message;
  EXPECT_TRUE(results.messages[1].stalled);
  EXPECT_NEAR(results.messages[1].position, 0.035, 0.002);

  // The same grasp with allow_stalling (ROS 2's parallel gripper) is a success.
  std::string load_out;
  const int load_rc = robot.run({"cmctl", "load", "grasp_controller"}, &load_out, 20);
  ASSERT_EQ(load_rc, 0) << load_out;
  std::string sw_out;
  const int sw_rc = robot.run({"cmctl", "switch", "--start", "grasp_controller", "--stop", "gripper_controller"}, &sw_out, 20);
  ASSERT_EQ(sw_rc, 0) << sw_out;
  std::string release_out;
  const int release_rc = robot.run({"gripper", "grasp_controller", "--position", "0.0"}, &release_out, 20);
  ASSERT_EQ(release_rc, 0) << release_out;
  std::string grasp_out;
  const int grasp_rc = robot.run({"gripper", "grasp_controller", "--position", "0.05"}, &grasp_out, 20);
  ASSERT_EQ(grasp_rc, 0) << grasp_out;
  EXPECT_TRUE(has(grasp_out, "grasp_controller: SUCCEEDED: stalled at 0.03")) << grasp_out;
  EXPECT_TRUE(has(grasp_out, "allow_stalling: succeeded")) << grasp_out;
  pump_until(lc, [&] { return grasps.messages.size() >= 2; }, 5);
  ASSERT_EQ(grasps.messages.size(), 2u);
  EXPECT_TRUE(grasps.messages[1].stalled);
  EXPECT_FALSE(grasps.messages[1].reached_goal);

  // A controller that takes no gripper goals is named with its type.
  std::string wrong_out;
  const int wrong_rc = robot.run({"gripper", "joint_state_controller", "--position", "0.01"}, &wrong_out, 20);
  EXPECT_EQ(wrong_rc, 1) << wrong_out;
  EXPECT_TRUE(has(wrong_out, "gripper: error: joint_state_controller "
                                  "(joint_state_controller/JointStateController) takes no commands (it only reads the "
                                  "joints and publishes joint_states); gripper_command_t was given on "
                                  "joint_state_controller/command"))
      << wrong_out;
  std::string stopped_out;
  const int stopped_rc = robot.run({"gripper", "gripper_controller", "--position", "0.01"}, &stopped_out, 20);
  EXPECT_EQ(stopped_rc, 1) << stopped_out;
  EXPECT_TRUE(has(stopped_out, "'gripper_controller' is loaded but stopped, not running: start it with `cmctl "
                                    "start gripper_controller`"))
      << stopped_out;
}

}  // namespace
}  // namespace lcm_control::testing
