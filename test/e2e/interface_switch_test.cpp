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
#include "test/e2e/session.hpp"
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
  RobotSession robot(source("test/robots/switch_arm.urdf"), source("test/robots/switch_arm.yaml"));
  lcm::LCM lc(robot.url());
  Latest<hardware_state_t> hw(lc, "hardware/state");
  robot.start_controller_manager();
  robot.start_sim({"--duration", "60"});
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"velocity_controller"}));
  ASSERT_TRUE(pump_until(lc, [&] { return hw.count > 0; }, 10)) << robot.sim_output();
  EXPECT_EQ(hw.last.mode[0], hardware_command_t::MODE_POSITION) << "before any command: the first interface";

  std::string go_out;
  const int go_rc = robot.run({"turret-cmd", "velocity_controller", "0.5", "-0.25"}, &go_out, 20);
  ASSERT_EQ(go_rc, 0) << go_out;
  ASSERT_TRUE(pump_until(
      lc, [&] { return hw.last.mode[0] == hardware_command_t::MODE_VELOCITY && std::abs(hw.last.velocity[0] - 0.5) < 1e-6; },
      10))
      << "mode " << int(hw.last.mode[0]) << " velocity " << hw.last.velocity[0] << "\n" << robot.cm_output() << robot.sim_output();
  EXPECT_EQ(hw.last.mode[1], hardware_command_t::MODE_VELOCITY);
  // The commanded speed, measured over a second of sim time.
  const hardware_state_t a = hw.last;
  ASSERT_TRUE(pump_until(lc, [&] { return hw.last.utime >= a.utime + 1000000; }, 10));
  const hardware_state_t b = hw.last;
  const double dt = double(b.utime - a.utime) * 1e-6;
  EXPECT_NEAR((b.position[0] - a.position[0]) / dt, 0.5, 5e-3);
  EXPECT_NEAR((b.position[1] - a.position[1]) / dt, -0.25, 5e-3);

  std::string load_out;
  const int load_rc = robot.run({"cmctl", "load", "position_controller"}, &load_out, 20);
  ASSERT_EQ(load_rc, 0) << load_out;
  std::string sw_out;
  const int sw_rc = robot.run({"cmctl", "switch", "--start", "position_controller", "--stop", "velocity_controller"}, &sw_out, 20);
  ASSERT_EQ(sw_rc, 0) << sw_out << robot.cm_output();
  // The position controller starts holding where the joints are: position mode, standing still.
  ASSERT_TRUE(pump_until(
      lc, [&] { return hw.last.mode[0] == hardware_command_t::MODE_POSITION && std::abs(hw.last.velocity[0]) < 1e-6; },
      10))
      << "mode " << int(hw.last.mode[0]) << " velocity " << hw.last.velocity[0];
  std::string to_out;
  const int to_rc = robot.run({"turret-cmd", "position_controller", "0.2", "0.3"}, &to_out, 20);
  ASSERT_EQ(to_rc, 0) << to_out;
  const bool reached = pump_until(
      lc,
      [&] { return std::abs(hw.last.position[0] - 0.2) < 1e-4 && std::abs(hw.last.position[1] - 0.3) < 1e-4; }, 10);
  EXPECT_TRUE(reached) << hw.last.position[0] << " " << hw.last.position[1];
  EXPECT_EQ(hw.last.mode[0], hardware_command_t::MODE_POSITION);
  EXPECT_EQ(hw.last.mode[1], hardware_command_t::MODE_POSITION);
  EXPECT_EQ(robot.stop_spawner(), 0) << robot.spawner_output();
  EXPECT_EQ(robot.stop_sim(), 0) << robot.sim_output();
  EXPECT_NE(robot.sim_output().find("0 commands dropped"), std::string::npos) << robot.sim_output();
  EXPECT_EQ(robot.stop_controller_manager(), 0) << robot.cm_output();
}

TEST(InterfaceSwitch, MockHardwareInLockstepFollowsCommandsExactlyWithTheMimicJoint) {
  RobotSession robot(source("test/robots/mock_arm.urdf"), source("test/robots/switch_arm.yaml"),
                     unique_lcm_url() + "&recv_buf_size=4194304");
  lcm::LCM lc(robot.url());
  Latest<hardware_state_t> hw(lc, "hardware/state");
  Latest<joint_state_t> js(lc, "joint_states");
  robot.start_controller_manager();
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_controller", "position_controller"}));
  ASSERT_NO_FATAL_FAILURE(robot.start_sim({"--mode", "lockstep"}, 20));
  ASSERT_NE(robot.sim_output().find("ready (lockstep, mock hardware"), std::string::npos) << robot.sim_output();
  ASSERT_TRUE(pump_until(lc, [&] { return js.count > 0; }, 10)) << robot.sim_output() << robot.cm_output();
  EXPECT_EQ(hw.last.position[0], 0.5);  // initial_value, held by the position controller
  EXPECT_DOUBLE_EQ(joint_state(js.last, "j3"), 0.1);

  std::string to_out;
  const int to_rc = robot.run({"turret-cmd", "position_controller", "0.3", "-0.4"}, &to_out, 20);
  ASSERT_EQ(to_rc, 0) << to_out;
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
  EXPECT_GT(rtf, 3.0) << "lockstep over LCM at 1 kHz; sim_server says: " << robot.sim_output();

  // Reset (sim_server/request) is the Bullet backend's: back to the start pose, which the restarted controller holds.
  std::string reset_out;
  const int reset_rc = robot.run({"cmctl", "reset"}, &reset_out, 20);
  ASSERT_EQ(reset_rc, 0) << reset_out << robot.sim_output();
  EXPECT_TRUE(pump_until(
      lc,
      [&] {
        return hw.last.position[0] == 0.5 && hw.last.position[1] == 0.0 && joint_state(js.last, "j3") == 0.1;
      },
      10))
      << hw.last.position[0] << " " << hw.last.position[1] << " j3 " << joint_state(js.last, "j3") << "\n"
      << robot.sim_output();
  EXPECT_EQ(robot.stop_sim(), 0) << robot.sim_output();
  EXPECT_EQ(robot.stop_spawner(), 0) << robot.spawner_output();
  EXPECT_EQ(robot.stop_controller_manager(), 0) << robot.cm_output();
  std::printf("mock hardware, lockstep over LCM at 1 kHz: %.1fx real time\n", rtf);
}

}  // namespace
}  // namespace lcm_control::testing
