// The gripper test robot end to end: one position controller closes the left
// finger, the right finger follows through its <mimic> in sim_server, both
// stop at the box, and joint_states carries the mimic joint.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lcm_control::testing {
namespace {

TEST(MimicGripper, ClosesOnTheBoxWithBothFingersAndPublishesTheMimicJoint) {
  const std::string url = unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  const std::string urdf = source("test/robots/gripper.urdf"), yaml = source("test/robots/gripper.yaml");
  lcm::LCM lc(url);
  Recorder<joint_state_t> states(lc, "joint_states");
  ChildProcess cm({bin("controller_manager"), "--urdf", urdf, "--config", yaml}, env);
  ChildProcess sim({bin("sim_server"), "--urdf", urdf, "--config", yaml}, env);
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "gripper_controller"}, env);
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 30)) << spawner.output() << cm.output() << sim.output();
  ChildProcess close({bin("turret-cmd"), "gripper_controller", "0.05"}, env);
  ASSERT_EQ(close.wait(20), 0) << close.output();
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
  ASSERT_FALSE(states.messages.empty()) << cm.output();
  const joint_state_t& last = states.messages.back();
  ASSERT_EQ(last.num_joints, 2);
  EXPECT_EQ(last.name[0], "left_finger_joint");
  EXPECT_EQ(last.name[1], "right_finger_joint");
  EXPECT_TRUE(settled) << "left finger at " << at(last, "left_finger_joint");
  EXPECT_NEAR(at(last, "right_finger_joint"), 0.035, 2e-3);  // stopped by the box, not at the 0.05 commanded
}

}  // namespace
}  // namespace lcm_control::testing
