// state-publisher end to end: joint_states in, link_poses matching hand-computed
// forward kinematics of turret_bot out.
#include <gtest/gtest.h>

#include <cmath>

#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

TEST(StatePublisher, TurretBotLinkPoses) {
  const std::string url = unique_lcm_url();
  ChildProcess p({bin("state-publisher"), "--urdf", source("config/turret_bot.urdf"), "--config",
                  source("config/turret_bot.yaml"), "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("ready: ", 5.0)) << p.output();
  lcm::LCM lc(url);
  Recorder<link_poses_t> rec(lc, "link_poses");
  const double configs[3][2] = {{0.0, 0.0}, {0.25, 1.5}, {0.9, -3.0}};
  for (int c = 0; c < 3; ++c) {
    joint_state_t js{};
    js.utime = 1000 * (c + 1);
    js.num_joints = 2;
    js.name = {"j2", "j1"};  // any order: matched by name
    js.position = {configs[c][1], configs[c][0]};
    js.velocity = {0, 0};
    js.effort = {0, 0};
    lc.publish("joint_states", &js);
    ASSERT_TRUE(pump_until(lc, [&] { return rec.messages.size() > size_t(c); }, 3.0)) << p.output();
    const link_poses_t& m = rec.messages[c];
    EXPECT_EQ(m.utime, js.utime);
    ASSERT_EQ(m.num_links, 3);
    EXPECT_EQ(m.name, (std::vector<std::string>{"base", "slider", "rotor"}));
    const double q1 = configs[c][0], q2 = configs[c][1];
    const std::vector<double> slider{0, q1, 0}, rotor{0, q1 + 0.05, 0.475};
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(m.position[0][k], 0, 1e-12);
      EXPECT_NEAR(m.position[1][k], slider[k], 1e-12);
      EXPECT_NEAR(m.position[2][k], rotor[k], 1e-12);
    }
    // Rotor: yaw q2 about z = quaternion (cos q2/2, 0, 0, sin q2/2), up to sign.
    const double sign = m.orientation[2][0] < 0 ? -1 : 1;
    EXPECT_NEAR(sign * m.orientation[2][0], std::cos(q2 / 2), 1e-12);
    EXPECT_NEAR(sign * m.orientation[2][3], std::sin(q2 / 2), 1e-12);
    EXPECT_NEAR(m.orientation[1][0], 1, 1e-12);
  }
  EXPECT_EQ(p.stop(5.0), 0) << p.output();
}

TEST(StatePublisher, BadUrdfIsOneLineAndExit3) {
  ChildProcess p({bin("state-publisher"), "--urdf", "/nonexistent/robot.urdf"});
  EXPECT_EQ(p.wait(5.0), 3);
  EXPECT_NE(p.output().find("state-publisher: error: /nonexistent/robot.urdf: URDF file not found"),
            std::string::npos)
      << p.output();
}
