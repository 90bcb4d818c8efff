// Robots as people bring them from ROS, end to end with the real programs, on
// the project's own test robots (test/robots): a namespaced YAML under launch,
// an arm whose default start is outside its limits, trajectories sent with
// send-trajectory. With ../shared/robots present, the real UR5 as well.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

std::string robot(const std::string& file) { return lt::source("test/robots/" + file); }

double position_of(const joint_state_t& s, const std::string& joint) {
  for (int k = 0; k < s.num_joints; ++k)
    if (s.name[k] == joint) return s.position[k];
  return NAN;
}

double velocity_of(const joint_state_t& s, const std::string& joint) {
  for (int k = 0; k < s.num_joints; ++k)
    if (s.name[k] == joint) return s.velocity[k];
  return NAN;
}

}  // namespace

TEST(RealRobots, NamespacedRobotUnderLaunchRunsItsThreeControllersInItsNamespace) {
  const std::string dir = lt::temp_dir("ns_bot_launch");
  const std::string file = dir + "/ns_bot.launch.yaml";
  std::ofstream(file) << "urdf: " << robot("ns_bot.urdf") << "\nconfig: " << robot("ns_bot.yaml")
                      << "\ncontrollers: [joint_state_controller, joint1_position_controller, "
                         "joint2_position_controller]\n";
  const std::string url = lt::unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  lcm::LCM lc(url);
  ASSERT_TRUE(lc.good());
  lt::Recorder<joint_state_t> states(lc, "ns_bot/joint_states");

  // No --namespace anywhere: the URDF's <robotNamespace>/ns_bot</robotNamespace> decides, for launch too.
  lt::ChildProcess launch({lt::bin("launch"), file, "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("started joint_state_controller, joint1_position_controller, "
                                     "joint2_position_controller",
                                     40))
      << launch.output();
  EXPECT_NE(launch.output().find("controllers read from 'ns_bot:', the robot's namespace"), std::string::npos)
      << launch.output();

  lt::ChildProcess list({lt::bin("cmctl"), "--namespace", "ns_bot", "list"}, env);
  ASSERT_EQ(list.wait(15), 0) << list.output();
  for (const char* c : {"joint_state_controller", "joint1_position_controller", "joint2_position_controller"})
    EXPECT_NE(list.output().find(c), std::string::npos) << list.output();

  ASSERT_TRUE(lt::pump_until(lc, [&] { return !states.messages.empty(); }, 10)) << "no ns_bot/joint_states";
  const joint_state_t before = states.messages.back();
  EXPECT_NEAR(position_of(before, "joint1"), 0.0, 0.01);
  lt::ChildProcess cmd({lt::bin("turret-cmd"), "--namespace", "ns_bot", "joint1_position_controller", "0.5"}, env);
  EXPECT_EQ(cmd.wait(15), 0) << cmd.output();
  // Three seconds of sim time later joint1 has settled near 0.5 (p 100 against the arm's weight, i_clamp 1: as
  // in Gazebo, a steady error of about 0.1 rad remains).
  ASSERT_TRUE(lt::pump_until(
      lc, [&] { return states.messages.back().utime - before.utime > 3'000'000 + 1'000'000; }, 20));
  const joint_state_t after = states.messages.back();
  EXPECT_NEAR(position_of(after, "joint1"), 0.55, 0.07);
  EXPECT_NEAR(velocity_of(after, "joint1"), 0.0, 0.01);
  EXPECT_EQ(launch.stop(20), 0) << launch.output();
}
