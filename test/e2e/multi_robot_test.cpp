// Several robots on one bus (issue 13): `launch --robots 2` starts two
// turret_bots in namespaces r0 and r1, each with its hardware loop on a port of
// its own (--hardware-lcm-url auto). The shared bus carries what people watch
// and no hardware/state; each robot's hardware URL carries its loop only; a
// command to one robot moves that robot only; in lockstep the two robots, run
// from one file, follow the tutorial bit for bit alike.
//
// One test: both halves use the namespaces r0 and r1 and hence the same
// hardware ports, which parallel tests would share.
#include <gtest/gtest.h>

#include <cmath>

#include "bus/bus.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

double joint(const joint_state_t& m, const std::string& name) {
  for (int i = 0; i < m.num_joints; ++i)
    if (m.name[size_t(i)] == name) return m.position[size_t(i)];
  ADD_FAILURE() << "no joint " << name;
  return NAN;
}

}  // namespace

TEST(MultiRobot, TwoTurretBotsShareTheBusAndKeepTheirLoopsApart) {
  // Real time: a command to r1 moves r1 only; the loops stay off the shared bus.
  {
    const std::string url = lt::unique_lcm_url();
    lt::ChildProcess launch({lt::bin("launch"), lt::source("config/turret_bot.launch.yaml"), "--robots", "2",
                             "--lcm-url", url});
    ASSERT_TRUE(launch.wait_for_output("[launch] up: 2 robots (r0, r1)", 40)) << launch.output();
    lcm::LCM shared(url), r1_hw(hardware_url_for("auto", url, "r1"));
    lt::Recorder<joint_state_t> js0(shared, "r0/joint_states"), js1(shared, "r1/joint_states");
    lt::Recorder<hardware_state_t> hw_on_shared(shared, "r1/hardware/state"), hw1(r1_hw, "r1/hardware/state"),
        hw0_on_r1(r1_hw, "r0/hardware/state");
    ASSERT_TRUE(lt::pump_until(r1_hw, [&] { return hw1.messages.size() >= 200; }, 5));
    lt::ChildProcess pub({lt::bin("bus"), "pub", "j1_controller/command", "float64_t", "data=0.5", "--namespace",
                          "r1", "--lcm-url", url});
    EXPECT_EQ(pub.wait(10), 0) << pub.output();
    const bool reached = lt::pump_until(
        shared, [&] { return !js1.messages.empty() && std::abs(joint(js1.messages.back(), "j1") - 0.5) < 0.01; }, 10);
    EXPECT_TRUE(reached) << (js1.messages.empty() ? "no r1/joint_states" : "r1's j1 did not reach 0.5");
    lt::pump_until(shared, [] { return false; }, 0.3);
    ASSERT_FALSE(js0.messages.empty());
    EXPECT_NEAR(joint(js0.messages.back(), "j1"), 0.0, 0.01) << "r0 moved too";
    EXPECT_TRUE(hw_on_shared.messages.empty()) << hw_on_shared.messages.size() << " hardware/state on the shared bus";
    lt::pump_until(r1_hw, [] { return false; }, 0.1);
    EXPECT_TRUE(hw0_on_r1.messages.empty()) << "r0's loop reached r1's hardware URL";
    EXPECT_EQ(launch.stop(20), 0) << launch.output();
    EXPECT_NE(launch.output().find("all 2 robots stopped"), std::string::npos) << launch.output();
  }

  // Lockstep: the tutorial's commands on both robots from one file; each ends at --duration, and the two
  // trajectories are the same bit for bit.
  {
    const std::string url = lt::unique_lcm_url();
    lcm::LCM shared(url);
    lt::Recorder<joint_state_t> js0(shared, "r0/joint_states"), js1(shared, "r1/joint_states");
    lt::ChildProcess launch({lt::bin("launch"), lt::source("config/turret_bot_demo.launch.yaml"), "--robots", "2",
                             "--duration", "4", "--lcm-url", url});
    while (launch.running()) shared.handleTimeout(20);
    lt::pump_until(shared, [] { return false; }, 0.2);
    ASSERT_EQ(launch.wait(60), 0) << launch.output();
    EXPECT_NE(launch.output().find("every robot's launch ended"), std::string::npos) << launch.output();
    ASSERT_GE(js0.messages.size(), 150u);
    ASSERT_EQ(js0.messages.size(), js1.messages.size());
    double worst_j2 = 0;
    for (size_t k = 0; k < js0.messages.size(); ++k) {
      const auto &a = js0.messages[k], &b = js1.messages[k];
      ASSERT_EQ(a.utime, b.utime) << k;
      ASSERT_EQ(a.position, b.position) << "r0 and r1 differ at t=" << a.utime * 1e-6;
      ASSERT_EQ(a.velocity, b.velocity) << k;
      const double t = double(a.utime) * 1e-6;
      if (t > 1.0) worst_j2 = std::max(worst_j2, std::abs(joint(a, "j2") - 3.14 * std::sin(std::floor(t * 60) / 100)));
    }
    EXPECT_NEAR(joint(js0.messages.back(), "j1"), 0.5, 0.01);
    EXPECT_LT(worst_j2, 0.5) << "j2 does not follow the sine";
  }
}
