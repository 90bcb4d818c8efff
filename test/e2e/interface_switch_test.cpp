// ROS 2 robots end to end, the real sim_server and controller_manager over LCM:
// (a) switch_arm in Bullet: a velocity group controller on joints whose first
// command interface is position drives them in velocity mode at the commanded
// speed; switching to a position group controller puts them back in position
// mode and on the commanded positions. (b) mock_arm on mock hardware in
// lockstep: position commands are the state exactly, the mimic joint follows,
// the loop runs faster than real time, and a reset returns to initial_value.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lcm_control::testing {
namespace {

// The newest message on a channel and how many came (a lockstep bus carries too many to keep).
template <class Msg>
class Latest {
 public:
  Latest(lcm::LCM& lc, const std::string& channel) {
    lc.subscribe(channel, &Latest::on, this)->setQueueCapacity(0);
  }
  Msg last{};
  long count = 0;

 private:
  void on(const lcm::ReceiveBuffer*, const std::string&, const Msg* m) {
    last = *m;
    ++count;
  }
};

double joint_state(const joint_state_t& m, const std::string& joint) {
  for (int k = 0; k < m.num_joints; ++k)
    if (m.name[k] == joint) return m.position[k];
  return NAN;
}

TEST(InterfaceSwitch, VelocityControllerOnAPositionFirstJointThenSwitchBackToPosition) {
  const std::string url = unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  const std::string urdf = source("test/robots/switch_arm.urdf"), yaml = source("test/robots/switch_arm.yaml");
  lcm::LCM lc(url);
  Latest<hardware_state_t> hw(lc, "hardware/state");
  ChildProcess cm({bin("controller_manager"), "--urdf", urdf, "--config", yaml}, env);
  ChildProcess sim({bin("sim_server"), "--urdf", urdf, "--config", yaml, "--duration", "60"}, env);
  ChildProcess spawner({bin("spawner"), "velocity_controller"}, env);
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 30)) << spawner.output() << cm.output() << sim.output();
  ASSERT_TRUE(pump_until(lc, [&] { return hw.count > 0; }, 10)) << sim.output();
  EXPECT_EQ(hw.last.mode[0], hardware_command_t::MODE_POSITION) << "before any command: the first interface";

  ChildProcess go({bin("turret-cmd"), "velocity_controller", "0.5", "-0.25"}, env);
  ASSERT_EQ(go.wait(20), 0) << go.output();
  ASSERT_TRUE(pump_until(
      lc, [&] { return hw.last.mode[0] == hardware_command_t::MODE_VELOCITY && std::abs(hw.last.velocity[0] - 0.5) < 1e-6; },
      10))
      << "mode " << int(hw.last.mode[0]) << " velocity " << hw.last.velocity[0] << "\n" << cm.output() << sim.output();
  EXPECT_EQ(hw.last.mode[1], hardware_command_t::MODE_VELOCITY);
  // The commanded speed, measured over a second of sim time.
  const hardware_state_t a = hw.last;
  ASSERT_TRUE(pump_until(lc, [&] { return hw.last.utime >= a.utime + 1000000; }, 10));
  const hardware_state_t b = hw.last;
  const double dt = double(b.utime - a.utime) * 1e-6;
  EXPECT_NEAR((b.position[0] - a.position[0]) / dt, 0.5, 5e-3);
  EXPECT_NEAR((b.position[1] - a.position[1]) / dt, -0.25, 5e-3);

  ChildProcess load({bin("cmctl"), "load", "position_controller"}, env);
  ASSERT_EQ(load.wait(20), 0) << load.output();
  ChildProcess sw({bin("cmctl"), "switch", "--start", "position_controller", "--stop", "velocity_controller"}, env);
  ASSERT_EQ(sw.wait(20), 0) << sw.output() << cm.output();
  // The position controller starts holding where the joints are: position mode, standing still.
  ASSERT_TRUE(pump_until(
      lc, [&] { return hw.last.mode[0] == hardware_command_t::MODE_POSITION && std::abs(hw.last.velocity[0]) < 1e-6; },
      10))
      << "mode " << int(hw.last.mode[0]) << " velocity " << hw.last.velocity[0];
  ChildProcess to({bin("turret-cmd"), "position_controller", "0.2", "0.3"}, env);
  ASSERT_EQ(to.wait(20), 0) << to.output();
  const bool reached = pump_until(
      lc,
      [&] { return std::abs(hw.last.position[0] - 0.2) < 1e-4 && std::abs(hw.last.position[1] - 0.3) < 1e-4; }, 10);
  EXPECT_TRUE(reached) << hw.last.position[0] << " " << hw.last.position[1];
  EXPECT_EQ(hw.last.mode[0], hardware_command_t::MODE_POSITION);
  EXPECT_EQ(hw.last.mode[1], hardware_command_t::MODE_POSITION);
  EXPECT_EQ(spawner.stop(10), 0) << spawner.output();
  EXPECT_EQ(sim.stop(10), 0) << sim.output();
  EXPECT_NE(sim.output().find("0 commands dropped"), std::string::npos) << sim.output();
  EXPECT_EQ(cm.stop(10), 0) << cm.output();
}

TEST(InterfaceSwitch, MockHardwareInLockstepFollowsCommandsExactlyWithTheMimicJoint) {
  const std::string url = unique_lcm_url() + "&recv_buf_size=4194304";
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  const std::string urdf = source("test/robots/mock_arm.urdf"), yaml = source("test/robots/switch_arm.yaml");
  lcm::LCM lc(url);
  Latest<hardware_state_t> hw(lc, "hardware/state");
  Latest<joint_state_t> js(lc, "joint_states");
  ChildProcess cm({bin("controller_manager"), "--urdf", urdf, "--config", yaml}, env);
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "position_controller"}, env);
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 30)) << spawner.output() << cm.output();
  ChildProcess sim({bin("sim_server"), "--urdf", urdf, "--config", yaml, "--mode", "lockstep"}, env);
  ASSERT_TRUE(sim.wait_for_output("ready (lockstep, mock hardware", 20)) << sim.output();
  ASSERT_TRUE(pump_until(lc, [&] { return js.count > 0; }, 10)) << sim.output() << cm.output();
  EXPECT_EQ(hw.last.position[0], 0.5);  // initial_value, held by the position controller
  EXPECT_DOUBLE_EQ(joint_state(js.last, "j3"), 0.1);

  ChildProcess to({bin("turret-cmd"), "position_controller", "0.3", "-0.4"}, env);
  ASSERT_EQ(to.wait(20), 0) << to.output();
  ASSERT_TRUE(pump_until(lc, [&] { return hw.last.position[1] == -0.4 && joint_state(js.last, "j2") == -0.4; }, 10))
      << hw.last.position[1];
  // The step that reached the command carries the finite difference (-200 rad/s); the next stands still.
  const int64_t reached_us = hw.last.utime;
  ASSERT_TRUE(pump_until(lc, [&] { return hw.last.utime > reached_us; }, 10));
  EXPECT_EQ(hw.last.position[0], 0.3);  // exactly: no physics in between
  EXPECT_EQ(hw.last.velocity[0], 0.0);  // calculate_dynamics: the finite difference, 0 once it stands
  EXPECT_EQ(hw.last.mode[0], hardware_command_t::MODE_POSITION);
  EXPECT_DOUBLE_EQ(joint_state(js.last, "j3"), -2 * -0.4 + 0.1);
  const double rtf = hw.last.real_time_factor;
  EXPECT_GT(rtf, 3.0) << "lockstep over LCM at 1 kHz; sim_server says: " << sim.output();

  // Reset (sim_server/request) is the Bullet backend's: back to the start pose, which the restarted controller holds.
  ChildProcess reset({bin("cmctl"), "reset"}, env);
  ASSERT_EQ(reset.wait(20), 0) << reset.output() << sim.output();
  EXPECT_TRUE(pump_until(
      lc,
      [&] {
        return hw.last.position[0] == 0.5 && hw.last.position[1] == 0.0 && joint_state(js.last, "j3") == 0.1;
      },
      10))
      << hw.last.position[0] << " " << hw.last.position[1] << " j3 " << joint_state(js.last, "j3") << "\n"
      << sim.output();
  EXPECT_EQ(sim.stop(10), 0) << sim.output();
  EXPECT_EQ(spawner.stop(10), 0) << spawner.output();
  EXPECT_EQ(cm.stop(10), 0) << cm.output();
  std::printf("mock hardware, lockstep over LCM at 1 kHz: %.1fx real time\n", rtf);
}

}  // namespace
}  // namespace lcm_control::testing
