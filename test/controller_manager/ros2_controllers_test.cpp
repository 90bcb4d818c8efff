// ros2_controllers' types with their ROS 2 parameters (joint_state_broadcaster, forward_command_controller,
// joint_trajectory_controller, diff_drive_controller's ROS 2 names) on ros2_bot.urdf, a <ros2_control> robot, and
// its ROS 2 parameter file, on the simulated rig.
#include <gtest/gtest.h>

#include <cmath>

#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"

using namespace lcm_control;
using lcm_control::testing::data;
using lcm_control::testing::Recorder;
using lcm_control::testing::trajectory_goal;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

struct Ros2Rig : lcm_control::testing::Rig {
  Ros2Rig() : Rig(cm::builtin_registry(), data("ros2_bot.urdf"), data("ros2_bot.yaml")) {}
};

// The rig with one controller's ROS 2 section replaced by `section` (YAML text).
RobotModel with_section(const std::string& name, const std::string& section) {
  RobotModel m = load_robot_model(data("ros2_bot.urdf"), data("ros2_bot.yaml"));
  for (auto& c : m.controllers)
    if (c.name == name) {
      const std::string type = c.type;
      c.params = YAML::Load(section);
      c.params["type"] = type;
    }
  return m;
}

std::string load_message(const RobotModel& model, const std::string& name) {
  Bus bus("memq://", "");
  cm::ControllerManager manager(model, bus, cm::builtin_registry());
  return manager.load(name).message;
}

}  // namespace

TEST(Ros2Controllers, TheParameterFileLoadsEveryRos2TypeAndOnlyTheVendorOneIsNotAvailable) {
  Ros2Rig rig;
  for (const auto& c : rig.cm->check_configured()) {
    if (c.name == "vendor_speed_scaling") {
      EXPECT_EQ(c.outcome, cm::ControllerCheck::NotImplemented);
      EXPECT_TRUE(has(c.message, "a vendor's controller, Universal_Robots_ROS_Driver) is not available here"))
          << c.message;
    } else {
      EXPECT_EQ(c.outcome, cm::ControllerCheck::Loads) << c.name << ": " << c.message;
    }
  }
  const cm::Reply r = rig.load("lift_trajectory");
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "lift_trajectory/not_a_ros_key: not a parameter of "
                             "joint_trajectory_controller/JointTrajectoryController; ignored"))
      << r.message;
  EXPECT_TRUE(has(r.message, "[position, velocity]: the joints are commanded in position")) << r.message;
}

TEST(Ros2Controllers, JointStateBroadcasterPublishesEveryCycleWithTheMimicJoint) {
  Ros2Rig rig;
  Recorder<joint_state_t> js(rig.bus.lcm(), "joint_states");
  rig.actuator("lift_actuator").position = 0.4;
  rig.start("joint_state_broadcaster");
  js.messages.clear();
  rig.cycle(10);
  ASSERT_EQ(js.messages.size(), 10u);  // no publish_rate: every cycle, as ROS 2
  const joint_state_t& m = js.messages.back();
  EXPECT_EQ(m.name, (std::vector<std::string>{"lift", "elbow", "twist", "left_wheel", "right_wheel", "finger"}));
  EXPECT_DOUBLE_EQ(m.position[0], 0.4);
  EXPECT_DOUBLE_EQ(m.position[5], 0.2);  // finger mimics lift x 0.5
}

TEST(Ros2Controllers, JointStateBroadcasterWithJointsAndInterfacesPublishesThoseAndNaNForTheRest) {
  Ros2Rig rig;
  Recorder<joint_state_t> js(rig.bus.lcm(), "joint_states");
  rig.actuator("elbow_actuator").velocity = 0.7;
  rig.start("positions_only");
  rig.cycle(3);
  ASSERT_FALSE(js.messages.empty());
  const joint_state_t& m = js.messages.back();
  EXPECT_EQ(m.name, (std::vector<std::string>{"elbow", "lift", "virtual"}));
  EXPECT_TRUE(std::isfinite(m.position[0]));
  EXPECT_TRUE(std::isnan(m.velocity[0]));
  EXPECT_TRUE(std::isnan(m.effort[1]));
  EXPECT_DOUBLE_EQ(m.position[2], 0.0);  // extra_joints: a name, published at 0

  const std::string note = load_message(with_section("positions_only", "{joints: [elbow]}"), "positions_only");
  EXPECT_TRUE(has(note, "joints without interfaces: every joint is published")) << note;
}

TEST(Ros2Controllers, ForwardCommandControllerTakesTheInterfaceItsParameterNames) {
  Ros2Rig rig;
  rig.start("elbow_forward");
  float64_array_t v{};
  v.data = {1.5};
  v.size = 1;
  rig.publish("elbow_forward/command", v);
  rig.cycle(100);
  EXPECT_NEAR(rig.joint("elbow").velocity, 1.5, 1e-9);
  EXPECT_EQ(rig.commands.back().mode[1], hardware_command_t::MODE_VELOCITY);

  const std::string bad = load_message(with_section("elbow_forward", "{joints: [elbow], interface_name: speed}"),
                                       "elbow_forward");
  EXPECT_TRUE(has(bad, "elbow_forward/interface_name: 'speed' is not a joint command interface; use position, "
                       "velocity or effort"))
      << bad;
  const std::string wrong = load_message(with_section("elbow_forward", "{joints: [elbow], interface_name: position}"),
                                         "elbow_forward");
  EXPECT_TRUE(has(wrong, "elbow") && has(wrong, "PositionJointInterface")) << wrong;
}

TEST(Ros2Controllers, MultiInterfaceForwardCommandControllerTakesOneInterface) {
  Ros2Rig rig;
  rig.start("twist_forward");
  float64_t e{};
  e.data = 2.0;
  rig.publish("twist_forward/command", e);
  rig.cycle(2);
  EXPECT_EQ(rig.commands.back().mode[2], hardware_command_t::MODE_EFFORT);
  EXPECT_DOUBLE_EQ(rig.commands.back().command[2], 2.0);
  const std::string two = load_message(
      with_section("twist_forward", "{joint: twist, interface_names: [position, velocity]}"), "twist_forward");
  EXPECT_TRUE(has(two, "twist_forward/interface_names: [position, velocity]: give one interface here")) << two;
}

TEST(Ros2Controllers, TrajectoryControllerOnPositionReachesItsGoalWithinTheConstraints) {
  Ros2Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "lift_trajectory/result");
  rig.start("lift_trajectory");
  rig.publish("lift_trajectory/command", trajectory_goal(7, {"lift"}, {{0.5, {0.3}}, {1.0, {0.6}}}));
  rig.cycle(1200);
  ASSERT_EQ(result.messages.size(), 1u);
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::SUCCEEDED) << result.messages[0].message;
  EXPECT_NEAR(rig.joint("lift").position, 0.6, 1e-3);
}

TEST(Ros2Controllers, GoalTimeZeroWaitsForTheGoalToleranceAndCmdTimeoutAbortsIt) {
  // A weak effort PID never brings twist within 1e-9: ROS 2's goal_time 0 waits for ever, cmd_timeout ends it.
  auto run = [](const std::string& extra, std::vector<trajectory_status_t>& results) {
    lcm_control::testing::Rig rig(cm::builtin_registry(), data("ros2_bot.urdf"), data("ros2_bot.yaml"));
    rig.cm = std::make_unique<cm::ControllerManager>(
        with_section("lift_trajectory", "{joints: [twist], command_interfaces: [effort], gains: {twist: {p: 0.001}}, "
                                        "constraints: {goal_time: 0, twist: {goal: 1e-9}}" + extra + "}"),
        rig.bus, cm::builtin_registry());
    Recorder<trajectory_status_t> result(rig.bus.lcm(), "lift_trajectory/result");
    rig.start("lift_trajectory");
    rig.publish("lift_trajectory/command", trajectory_goal(3, {"twist"}, {{0.2, {0.5}}}));
    rig.cycle(1000);
    results = result.messages;
  };
  std::vector<trajectory_status_t> waits, aborted;
  run("", waits);
  EXPECT_TRUE(waits.empty());
  run(", cmd_timeout: 0.3", aborted);
  ASSERT_EQ(aborted.size(), 1u);
  EXPECT_EQ(aborted[0].status, trajectory_status_t::ABORTED) << aborted[0].message;
  EXPECT_NEAR(aborted[0].utime * 1e-6, 0.5, 0.01);  // the end (0.2 s after the goal) + 0.3 s

  const std::string off = load_message(
      with_section("lift_trajectory",
                   "{joints: [lift], command_interfaces: [position], constraints: {goal_time: 2}, cmd_timeout: 1}"),
      "lift_trajectory");
  EXPECT_TRUE(has(off, "cmd_timeout: 1 s is not more than constraints/goal_time 2 s, so it is off")) << off;
}

TEST(Ros2Controllers, TrajectoryWithoutInterpolationStepsToTheNextWaypoint) {
  Ros2Rig rig;
  rig.start("lift_steps");
  const size_t first = rig.commands.size();
  rig.publish("lift_steps/command", trajectory_goal(1, {"lift"}, {{0.1, {0.3}}, {0.2, {0.5}}}));
  rig.cycle(300);
  // Until 0.1 s the start (0); from 0.1 s to 0.2 s the next waypoint (0.5); then the last (0.5).
  std::vector<double> seen;
  for (size_t k = first; k < rig.commands.size(); ++k) {
    const double c = rig.commands[k].command[0];
    if (seen.empty() || std::abs(seen.back() - c) > 1e-9) seen.push_back(c);
  }
  ASSERT_EQ(seen.size(), 2u) << ::testing::PrintToString(seen);
  EXPECT_NEAR(seen[0], 0.0, 1e-12);
  EXPECT_NEAR(seen[1], 0.5, 1e-12);
}

TEST(Ros2Controllers, TrajectoryControllerOnVelocityUsesItsRos2Gains) {
  Ros2Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "elbow_trajectory/result");
  rig.start("elbow_trajectory");
  rig.publish("elbow_trajectory/command", trajectory_goal(2, {"elbow"}, {{1.0, {0.8}}}));
  rig.cycle(1500);
  ASSERT_EQ(result.messages.size(), 1u);
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::SUCCEEDED) << result.messages[0].message;
  EXPECT_NEAR(rig.joint("elbow").position, 0.8, 0.01);
  EXPECT_EQ(rig.commands.back().mode[1], hardware_command_t::MODE_VELOCITY);

  const std::string none = load_message(with_section("elbow_trajectory", "{joints: [elbow], command_interfaces: [velocity]}"),
                                        "elbow_trajectory");
  EXPECT_TRUE(has(none, "no gains: every gain is 0, so the velocity command is 0, as in ROS 2")) << none;
  const std::string bad = load_message(
      with_section("elbow_trajectory", "{joints: [elbow], command_interfaces: [acceleration]}"), "elbow_trajectory");
  EXPECT_TRUE(has(bad, "elbow_trajectory/command_interfaces: [acceleration] is not a combination ROS 2 allows")) << bad;
  const std::string state = load_message(
      with_section("elbow_trajectory",
                   "{joints: [elbow], command_interfaces: [velocity], state_interfaces: [velocity]}"),
      "elbow_trajectory");
  EXPECT_TRUE(has(state, "state_interfaces: [velocity]: use [position]")) << state;
}

TEST(Ros2Controllers, DiffDriveReadsRos2WheelNamesAndLimitsWithoutHasFlags) {
  Ros2Rig rig;
  rig.start("base");
  twist_t t{};
  t.linear.x = 2.0;  // over linear.x.max_velocity 0.5
  rig.publish("base/cmd_vel", t);
  rig.cycle(200);
  // 0.5 m/s on wheels of radius 0.1: 5 rad/s each.
  EXPECT_NEAR(rig.joint("left_wheel").velocity, 5.0, 1e-6);
  EXPECT_NEAR(rig.joint("right_wheel").velocity, 5.0, 1e-6);
}

// position_feedback (ROS 2, default true): odometry from the wheels' positions, or with false from their
// velocities. With encoders that never count (the positions stay 0), only the velocities see the base move.
// use_sim_time, which every ROS 2 node has, loads without a word.
TEST(Ros2Controllers, DiffDriveOdometryFromWheelVelocitiesWithoutPositionFeedback) {
  for (const bool feedback : {true, false}) {
    Ros2Rig rig;
    for (auto& c : rig.model.controllers)
      if (c.name == "base") {
        c.params["position_feedback"] = feedback;
        c.params["use_sim_time"] = true;
      }
    rig.cm = std::make_unique<cm::ControllerManager>(rig.model, rig.bus, cm::builtin_registry());
    Recorder<odometry_t> odom(rig.bus.lcm(), "base/odom");
    rig.cycle();
    const cm::Reply loaded = rig.load("base");
    ASSERT_TRUE(loaded.ok) << loaded.message;
    EXPECT_FALSE(has(loaded.message, "position_feedback")) << loaded.message;
    EXPECT_FALSE(has(loaded.message, "use_sim_time")) << loaded.message;
    ASSERT_TRUE(rig.switch_({"base"}, {}).ok);
    twist_t t{};
    t.linear.x = 0.4;
    for (int k = 0; k < 1000; ++k) {
      if (k % 100 == 0) rig.publish("base/cmd_vel", t);
      rig.cycle();
      for (auto& a : rig.act)
        if (a.name.find("wheel") != std::string::npos) a.position = 0;
    }
    ASSERT_FALSE(odom.messages.empty());
    const double x = odom.messages.back().position.x;
    if (feedback)
      EXPECT_NEAR(x, 0.0, 1e-9) << "from positions that never moved";
    else
      EXPECT_NEAR(x, 0.4, 0.02) << "from the wheels' 4 rad/s for a second";
  }
}

// publish_cmd (ROS 1) / publish_limited_velocity (ROS 2): the twist after the limits on <name>/cmd_vel_out, every
// update; a ROS parameter it does not read (enable_odom_tf) is named when the controller loads.
TEST(Ros2Controllers, DiffDrivePublishesTheLimitedTwistOnCmdVelOut) {
  lcm_control::testing::Rig rig(cm::builtin_registry(), data("ros2_bot.urdf"), data("diff_drive_publish_cmd.yaml"));
  Recorder<twist_t> out(rig.bus.lcm(), "base/cmd_vel_out");
  rig.cycle();
  const cm::Reply loaded = rig.load("base");
  ASSERT_TRUE(loaded.ok) << loaded.message;
  EXPECT_TRUE(has(loaded.message, "enable_odom_tf: known ROS parameter of diff_drive_controller/DiffDriveController, "
                                  "not supported yet; ignored"))
      << loaded.message;
  EXPECT_FALSE(has(loaded.message, "publish_limited_velocity")) << loaded.message;
  ASSERT_TRUE(rig.switch_({"base"}, {}).ok);
  out.messages.clear();
  twist_t t{};
  t.linear.x = 2.0;  // over linear.x.max_velocity 0.5
  t.angular.z = 0.3;
  rig.publish("base/cmd_vel", t);
  rig.cycle(100);
  ASSERT_GE(out.messages.size(), 99u);
  EXPECT_NEAR(out.messages.back().linear.x, 0.5, 1e-12);
  EXPECT_NEAR(out.messages.back().angular.z, 0.3, 1e-12);

  // Without the flag nothing is published there; ROS 1's name for it is read too.
  for (const std::string flag : {"", "publish_cmd: true, "}) {
    lcm_control::testing::Rig plain(cm::builtin_registry(), data("ros2_bot.urdf"), data("ros2_bot.yaml"));
    if (!flag.empty()) {
      const std::string msg = load_message(
          with_section("base", "{" + flag + "left_wheel_names: [left_wheel], right_wheel_names: [right_wheel], "
                                          "wheel_separation: 0.6, wheel_radius: 0.1}"),
          "base");
      EXPECT_FALSE(has(msg, "publish_cmd")) << msg;
      continue;
    }
    Recorder<twist_t> none(plain.bus.lcm(), "base/cmd_vel_out");
    plain.start("base");
    plain.publish("base/cmd_vel", t);
    plain.cycle(50);
    EXPECT_TRUE(none.messages.empty());
  }
}
