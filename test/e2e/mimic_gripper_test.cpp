// The gripper test robot end to end: one position controller closes the left
// finger, the right finger follows through its <mimic> in sim_server, both
// stop at the box, and joint_states carries the mimic joint.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lcm_control/joint_state_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lcm_control::testing {
namespace {

TEST(MimicGripper, ClosesOnTheBoxWithBothFingersAndPublishesTheMimicJoint) {
  RobotSession robot(source("test/robots/gripper.urdf"), source("test/robots/gripper.yaml"));
  lcm::LCM lc(robot.url());
  Recorder<joint_state_t> states(lc, "joint_states");
  robot.start_controller_manager();
  robot.start_sim();
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_controller", "gripper_controller"}));
  std::string close_output;
  ASSERT_EQ(robot.run({"turret-cmd", "gripper_controller", "0.05"}, &close_output, 20), 0) << close_output;
  auto at = [&](const joint_state_t& m, const std::string& joint) {
    for (int k = 0; k < m.num_joints; ++k)
      if (m.name[k] == joint) return m.position[k];
    return double(NAN);
  };
  const bool settled = pump_until(
      lc,
      [&] {
        return states.messages.size() > 50 && std::abs(at(states.messages.back(), "left_finger_joint") - 0.035) < 2e-3;
      },
      10);
  ASSERT_FALSE(states.messages.empty()) << robot.cm_output();
  const joint_state_t& last = states.messages.back();
  ASSERT_EQ(last.num_joints, 2);
  EXPECT_EQ(last.name[0], "left_finger_joint");
  EXPECT_EQ(last.name[1], "right_finger_joint");
  EXPECT_TRUE(settled) << "left finger at " << at(last, "left_finger_joint");
  EXPECT_NEAR(at(last, "right_finger_joint"), 0.035, 2e-3);  // stopped by the box, not at the 0.05 commanded
}

TEST(MimicGripper, PublishMimicJointsFalseLeavesTheMimicJointOutAsRosDoes) {
  // gripper_ros_joint_states.yaml, merged after gripper.yaml, sets publish_mimic_joints: false.
  RobotSession robot(source("test/robots/gripper.urdf"), source("test/robots/gripper.yaml"));
  lcm::LCM lc(robot.url());
  Recorder<joint_state_t> states(lc, "joint_states");
  robot.start_controller_manager({"--config", source("test/robots/gripper_ros_joint_states.yaml")});
  robot.start_sim();
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_controller", "gripper_controller"}));
  ASSERT_TRUE(pump_until(lc, [&] { return !states.messages.empty(); }, 10)) << robot.cm_output();
  const joint_state_t& last = states.messages.back();
  ASSERT_EQ(last.num_joints, 1);
  EXPECT_EQ(last.name[0], "left_finger_joint");
  std::string list;
  ASSERT_EQ(robot.run({"cmctl", "list"}, &list, 15), 0) << list;
  EXPECT_NE(list.find("joint_state_controller"), std::string::npos) << list;
  EXPECT_EQ(list.find("right_finger_joint"), std::string::npos) << list;
}

TEST(MimicGripper, CmctlListsEveryJointJointStatesPublishesByItsOwnName) {
  RobotSession robot(source("test/robots/gripper.urdf"), source("test/robots/gripper.yaml"));
  robot.start_controller_manager();
  robot.start_sim();
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_controller", "gripper_controller"}));
  std::string list;
  ASSERT_EQ(robot.run({"cmctl", "list"}, &list, 15), 0) << list;
  const size_t jsc = list.find("joint_state_controller");
  ASSERT_NE(jsc, std::string::npos) << list;
  const std::string line = list.substr(jsc, list.find('\n', jsc) - jsc);
  EXPECT_NE(line.find("left_finger_joint"), std::string::npos) << list;
  EXPECT_NE(line.find("right_finger_joint"), std::string::npos) << list;
}

}  // namespace
}  // namespace lcm_control::testing
