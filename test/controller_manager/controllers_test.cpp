// Each controller family driven in-process through the real loop (memq:// bus,
// simulated actuators): what it commands, how it starts, its parameters.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "controller_manager/gains.hpp"
#include "lcm_control/controller_state_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "rt/clock.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::Recorder;
using lcm_control::testing::Rig;
using lcm_control::testing::trajectory_goal;

namespace {
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
float64_t value(double v) {
  float64_t m{};
  m.data = v;
  return m;
}
float64_array_t values(std::vector<double> v) {
  float64_array_t m{};
  m.size = static_cast<int32_t>(v.size());
  m.data = v;
  return m;
}
}  // namespace

TEST(ControllerManagerLoad, RefusalsSayWhy) {
  Rig rig;
  Reply r = rig.load("nothere");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "no 'nothere' entry with a type in the config")) << r.message;
  EXPECT_TRUE(has(r.message, "joint_state_controller, jsc_subset")) << r.message;
  r = rig.load("typo_type");
  EXPECT_TRUE(has(r.message,
                  "controller type 'position_controllers/JointPositionControler' does not exist; did you "
                  "mean 'position_controllers/JointPositionController'?"))
      << r.message;
  r = rig.load("wrong_interface");
  EXPECT_TRUE(has(r.message,
                  "controller 'wrong_interface' needs VelocityJointInterface on joint 'slide', but "
                  "transmission 't_slide' offers only PositionJointInterface"))
      << r.message;
  r = rig.load("missing_joint");
  EXPECT_TRUE(has(r.message, "joint 'elbow' is not in the URDF")) << r.message;
  r = rig.load("no_publish_rate");
  EXPECT_TRUE(has(r.message, "no_publish_rate/publish_rate: missing (required)")) << r.message;
  EXPECT_TRUE(rig.load("slide_position").ok);
  r = rig.load("slide_position");
  EXPECT_TRUE(has(r.message, "already loaded")) << r.message;
  EXPECT_EQ(rig.cm->list().size(), 1u);
}

TEST(ControllerManagerLoad, UnloadIsRefusedWhileRunning) {
  Rig rig;
  rig.start("slide_position");
  Reply r = rig.cm->unload("slide_position");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "cannot unload 'slide_position': it is running; stop it first")) << r.message;
  EXPECT_TRUE(rig.switch_({}, {"slide_position"}).ok);
  EXPECT_EQ(rig.cm->list()[0].state, "stopped");
  EXPECT_TRUE(rig.cm->unload("slide_position").ok);
  EXPECT_FALSE(rig.cm->unload("slide_position").ok);
}

TEST(ControllerManagerForwardCommand, PositionStartsAtTheCurrentPositionThenFollows) {
  Rig rig;
  rig.actuator("slide_motor").position = 0.3;
  rig.cycle(3);
  rig.start("slide_position");
  rig.cycle(5);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.3);  // held, no jump to 0
  rig.publish("slide_position/command", value(0.8));
  rig.cycle(2);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.8);
  rig.publish("slide_position/command", value(NAN));
  rig.cycle(2);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.8);
}

TEST(ControllerManagerForwardCommand, VelocityGoesThroughTheTransmission) {
  Rig rig;
  rig.start("wheel_velocity");
  rig.cycle(3);
  EXPECT_EQ(rig.actuator("wheel_motor").velocity, 0.0);
  rig.publish("wheel_velocity/command", value(2.0));
  rig.cycle(1001);
  EXPECT_DOUBLE_EQ(rig.actuator("wheel_motor").velocity, 20.0);  // reduction 10
  EXPECT_NEAR(rig.joint("wheel").velocity, 2.0, 1e-12);
  EXPECT_NEAR(rig.joint("wheel").position, 0.5 + 2.0, 0.01);  // offset 0.5, 1 s at 2 rad/s
}

TEST(ControllerManagerForwardCommand, EffortStartsAtZeroThenForwards) {
  Rig rig;
  rig.start("arm_effort");
  rig.cycle(2);
  EXPECT_EQ(rig.commands.back().command[2], 0.0);
  rig.publish("arm_effort/command", value(5.0));
  rig.cycle(2);
  EXPECT_EQ(rig.commands.back().mode[2], hardware_command_t::MODE_EFFORT);
  EXPECT_EQ(rig.commands.back().command[2], 5.0);
  EXPECT_GT(rig.actuator("arm_motor").velocity, 0.0);
}

TEST(ControllerManagerForwardCommand, GroupsTakeOneValuePerJointAndCountWrongSizes) {
  Rig rig;
  rig.start("pos_group");
  rig.start("vel_group");
  rig.start("eff_group");
  rig.publish("pos_group/command", values({0.2, -1.0}));
  rig.publish("vel_group/command", values({1.0, -2.0}));
  rig.publish("eff_group/command", values({3.0, 4.0}));
  rig.cycle(2);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.2);
  EXPECT_DOUBLE_EQ(rig.actuator("tilt_motor").position, -1.0);
  EXPECT_DOUBLE_EQ(rig.actuator("wheel_motor").velocity, 10.0);
  EXPECT_DOUBLE_EQ(rig.actuator("roll_motor").velocity, -2.0);
  EXPECT_DOUBLE_EQ(rig.actuator("spin_motor").effort, 3.0);
  EXPECT_DOUBLE_EQ(rig.actuator("arm_motor").effort, 4.0);
  rig.publish("pos_group/command", values({0.5}));
  rig.publish("pos_group/command", values({0.5, 0.6, 0.7}));
  rig.cycle(2);
  EXPECT_DOUBLE_EQ(rig.actuator("slide_motor").position, 0.2);
  const auto stats = rig.cm->statistics();
  EXPECT_EQ(stats.dropped, 2);
}

TEST(ControllerManagerJointStateController, PublishesFirstCycleAtItsRateInTransmissionOrder) {
  Rig rig;
  Recorder<joint_state_t> js(rig.bus.lcm(), "joint_states");
  rig.start("joint_state_controller");
  rig.cycle(1);
  ASSERT_EQ(js.messages.size(), 1u);  // first cycle
  rig.cycle(999);
  EXPECT_NEAR(static_cast<double>(js.messages.size()), 60.0, 1.0);
  EXPECT_EQ(js.messages[0].name, (std::vector<std::string>{"tilt", "slide", "arm", "wheel", "spin", "roll"}));
  EXPECT_DOUBLE_EQ(js.messages[0].position[3], 0.5);  // wheel: actuator 0 + offset
  // Intervals are 1/60 s on the hardware clock, to the step.
  for (size_t k = 2; k < js.messages.size(); ++k)
    EXPECT_NEAR(js.messages[k].utime - js.messages[k - 1].utime, 16667, 1000);
}

TEST(ControllerManagerJointStateController, KeepsItsRateAfterTimeJumps) {
  Rig rig;
  Recorder<joint_state_t> js(rig.bus.lcm(), "joint_states");
  rig.start("joint_state_controller");
  rig.cycle(500);
  size_t n = js.messages.size();
  rig.time_offset_us = 100000000;  // +100 s: no burst to catch up
  rig.cycle(500);
  EXPECT_NEAR(static_cast<double>(js.messages.size() - n), 30.0, 1.0);
  n = js.messages.size();
  rig.time_offset_us = -400000;  // back in time (a reset): publishes at once, same rate
  rig.cycle(1);
  EXPECT_EQ(js.messages.size(), n + 1);
  rig.cycle(499);
  EXPECT_NEAR(static_cast<double>(js.messages.size() - n), 30.0, 1.0);
}

TEST(ControllerManagerJointStateController, SubsetOrderAndExtraJoints) {
  Rig rig;
  Recorder<joint_state_t> js(rig.bus.lcm(), "joint_states");
  const Reply r = rig.load("jsc_subset");
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "extra_joints[1]: joint 'slide' is already published; skipped")) << r.message;
  ASSERT_TRUE(rig.switch_({"jsc_subset"}, {}).ok);
  rig.actuator("arm_motor").position = 0.25;
  rig.cycle(1);
  ASSERT_FALSE(js.messages.empty());
  const auto& m = js.messages.back();
  EXPECT_EQ(m.name, (std::vector<std::string>{"arm", "slide", "virtual"}));
  EXPECT_DOUBLE_EQ(m.position[0], 0.25);
  EXPECT_DOUBLE_EQ(m.position[2], 1.0);
  EXPECT_DOUBLE_EQ(m.velocity[2], 0.5);
  EXPECT_DOUBLE_EQ(m.effort[2], 2.0);
}

TEST(ControllerManagerJointStateController, FrankasStateControllerPublishesJointStatesOfItsJointNames) {
  Rig rig;
  Recorder<joint_state_t> js(rig.bus.lcm(), "joint_states");
  rig.cycle();
  const Reply r = rig.load("franka_state");
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "publishes joint_states only (franka_states has no equivalent here)")) << r.message;
  EXPECT_FALSE(has(r.message, "arm_id")) << r.message;  // read, not reported as unknown
  ASSERT_TRUE(rig.switch_({"franka_state"}, {}).ok);
  rig.cycle(1000);
  EXPECT_NEAR(static_cast<double>(js.messages.size()), 30.0, 1.0);
  ASSERT_FALSE(js.messages.empty());
  EXPECT_EQ(js.messages[0].name, (std::vector<std::string>{"tilt", "arm"}));
}

TEST(ControllerManagerPidControllers, EffortPositionHoldsAGravityLoadedJoint) {
  Rig rig;
  auto& arm = rig.actuator("arm_motor");
  arm.gravity = 10.0;
  arm.inertia = 0.2;
  arm.position = 0.5;
  rig.start("arm_position");
  double worst = 0;
  for (int k = 0; k < 3000; ++k) {
    rig.cycle();
    worst = std::max(worst, std::abs(rig.actuator("arm_motor").position - 0.5));
  }
  EXPECT_LT(worst, 0.01);
  rig.publish("arm_position/command", value(1.0));
  rig.cycle(3000);
  EXPECT_NEAR(rig.actuator("arm_motor").position, 1.0, 0.01);
}

TEST(ControllerManagerPidControllers, PositionErrorIsShortestAngleOnlyForContinuousJoints) {
  Rig rig;
  rig.actuator("wheel_motor").position = (0.2 - 0.5) * 10;  // wheel joint at 0.2
  rig.actuator("arm_motor").position = -2.9;
  rig.start("wheel_position");
  rig.start("arm_position");
  rig.publish("wheel_position/command", value(2 * M_PI - 0.2));
  rig.publish("arm_position/command", value(2.9));
  rig.cycle(1);
  EXPECT_LT(rig.commands.back().command[3], 0.0);  // wheel goes -0.4 rad, not +5.88
  EXPECT_GT(rig.commands.back().command[2], 0.0);  // revolute arm goes the long way: its limits say so
  rig.cycle(3000);
  EXPECT_NEAR(rig.joint("wheel").position, -0.2, 0.01);
}

TEST(ControllerManagerPidControllers, EffortVelocityReachesItsSetPointAndPublishesState) {
  Rig rig;
  Recorder<controller_state_t> st(rig.bus.lcm(), "spin_velocity/state");
  rig.start("spin_velocity");
  rig.publish("spin_velocity/command", value(3.0));
  rig.cycle(3000);
  EXPECT_NEAR(rig.actuator("spin_motor").velocity, 3.0, 0.05);
  ASSERT_GE(st.messages.size(), 299u);  // every 10th update
  EXPECT_EQ(st.messages.back().joint, "spin");
  EXPECT_DOUBLE_EQ(st.messages.back().set_point, 3.0);
  EXPECT_NEAR(st.messages.back().process_value, 3.0, 0.05);
}

TEST(ControllerManagerPidControllers, GainsAtRunTime) {
  Rig rig;
  ASSERT_TRUE(rig.load("arm_position").ok);
  Controller& c = *rig.cm->loop().slots()[0]->controller;
  pid_gains_t req, ans;
  req.query = true;
  ans = answer_gains("arm_position", pid_lookup(c), req, 0);
  EXPECT_TRUE(ans.ok) << ans.message;
  EXPECT_EQ(ans.joint, "arm");
  EXPECT_EQ(ans.p, 1000);
  EXPECT_EQ(ans.i_clamp_max, 10);
  req = pid_gains_t{};
  req.joint = "arm";
  req.p = 7;
  req.d = 1;
  req.i_clamp_min = -2;
  req.i_clamp_max = 2;
  ans = answer_gains("arm_position", pid_lookup(c), req, 0);
  EXPECT_TRUE(ans.ok) << ans.message;
  EXPECT_EQ(c.pid("arm")->gains().p, 7);
  req.p = NAN;
  ans = answer_gains("arm_position", pid_lookup(c), req, 0);
  EXPECT_FALSE(ans.ok);
  EXPECT_TRUE(has(ans.message, "p is not a finite number")) << ans.message;
  EXPECT_EQ(ans.p, 7);
  req.joint = "slide";
  ans = answer_gains("arm_position", pid_lookup(c), req, 0);
  EXPECT_FALSE(ans.ok);
  EXPECT_TRUE(has(ans.message, "no PID for joint 'slide'")) << ans.message;
}

TEST(ControllerManagerPidControllers, GainsOverLcm) {
  Rig rig;
  Recorder<pid_gains_t> answers(rig.bus.lcm(), "spin_velocity/gains");
  ASSERT_TRUE(rig.load("spin_velocity").ok);
  pid_gains_t req{};
  req.request_id = 9;
  req.p = 11;
  rig.publish("spin_velocity/gains/set", req);
  ASSERT_EQ(answers.messages.size(), 1u);
  EXPECT_TRUE(answers.messages[0].ok) << answers.messages[0].message;
  EXPECT_EQ(answers.messages[0].request_id, 9);
  EXPECT_EQ(answers.messages[0].p, 11);
}

TEST(ControllerManagerTrajectoryController, FollowsThreeWaypointsAndSucceeds) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "trajectory/result");
  Recorder<trajectory_status_t> feedback(rig.bus.lcm(), "trajectory/feedback");
  rig.start("trajectory");
  rig.cycle(2);
  rig.publish("trajectory/command",
              trajectory_goal(1, {"tilt", "slide"}, {{0.5, {0.3, 0.2}}, {1.0, {-0.4, 0.6}}, {1.5, {0.1, 0.5}}}));
  rig.cycle(2500);
  ASSERT_EQ(result.messages.size(), 1u);
  const auto& r = result.messages[0];
  EXPECT_EQ(r.status, trajectory_status_t::SUCCEEDED) << r.message;
  EXPECT_TRUE(has(r.message, "goal 1 reached")) << r.message;
  EXPECT_NEAR(rig.actuator("tilt_motor").position, 0.1, 1e-9);
  EXPECT_NEAR(rig.actuator("slide_motor").position, 0.5, 1e-9);
  EXPECT_GE(feedback.messages.size(), 25u);  // 20 Hz over ~1.5 s
}

TEST(ControllerManagerTrajectoryController, ImpossiblePathToleranceFailsNamingJointAndError) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "trajectory_tight/result");
  rig.start("trajectory_tight");
  rig.publish("trajectory_tight/command",
              trajectory_goal(2, {"slide", "tilt"}, {{0.5, {0.3, 0.0}}, {1.0, {0.6, 0.0}}, {1.5, {0.5, 0.0}}}));
  rig.cycle(2000);
  ASSERT_EQ(result.messages.size(), 1u);
  const auto& r = result.messages[0];
  EXPECT_EQ(r.status, trajectory_status_t::PATH_TOLERANCE_VIOLATED);
  EXPECT_TRUE(has(r.message, "path tolerance violated on joint 'slide': error ")) << r.message;
  EXPECT_TRUE(has(r.message, "exceeds 0.000001")) << r.message;
}

TEST(ControllerManagerTrajectoryController, BadGoalsAreRejectedAndNewGoalsPreempt) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "trajectory/result");
  rig.start("trajectory");
  rig.publish("trajectory/command", trajectory_goal(3, {"tilt"}, {{1.0, {0.3}}}));
  rig.publish("trajectory/command", trajectory_goal(4, {"tilt", "slide"}, {{1.0, {0.3, 5.0}}}));
  rig.publish("trajectory/command", trajectory_goal(5, {"tilt", "slide"}, {{1.0, {0.3, 0.5}}, {0.5, {0.3, 0.5}}}));
  ASSERT_EQ(result.messages.size(), 2u);
  EXPECT_TRUE(has(result.messages[0].message, "joint 'slide' is missing")) << result.messages[0].message;
  EXPECT_TRUE(has(result.messages[1].message, "time_from_start 0.5 must be greater than 1"))
      << result.messages[1].message;
  for (const auto& m : result.messages) EXPECT_EQ(m.status, trajectory_status_t::REJECTED);
  // Goal 4 put slide beyond its limits: accepted (as ROS), and now replaced.
  rig.publish("trajectory/command", trajectory_goal(44, {"tilt", "slide"}, {{1.0, {0.3, 0.5}}}));
  ASSERT_EQ(result.messages.size(), 3u);
  EXPECT_EQ(result.messages[2].goal_id, 4);
  EXPECT_EQ(result.messages[2].status, trajectory_status_t::PREEMPTED);
  EXPECT_TRUE(has(result.messages[2].message, "point 0 puts joint 'slide' at 5, beyond its limits [0, 1]"))
      << result.messages[2].message;
  result.messages.erase(result.messages.begin() + 2);
  rig.publish("trajectory/command", trajectory_goal(6, {"tilt", "slide"}, {{1.0, {0.3, 0.5}}}));
  rig.cycle(100);
  rig.publish("trajectory/command", trajectory_goal(7, {"tilt", "slide"}, {{1.0, {0.0, 0.0}}}));
  ASSERT_EQ(result.messages.size(), 4u);
  EXPECT_EQ(result.messages[3].status, trajectory_status_t::PREEMPTED);
  EXPECT_EQ(result.messages[3].goal_id, 6);
  rig.cycle(1700);
  ASSERT_EQ(result.messages.size(), 5u);
  EXPECT_EQ(result.messages[4].status, trajectory_status_t::SUCCEEDED) << result.messages[4].message;
}

// A goal's points without velocities after one whose points had them: each goal
// is read on its own (a reused LCM message would keep the old velocities).
TEST(ControllerManagerTrajectoryController, AGoalWithoutVelocitiesAfterOneWithThem) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "trajectory/result");
  rig.start("trajectory");
  joint_trajectory_t with = trajectory_goal(9, {"tilt", "slide"}, {{0.5, {0.2, 0.2}}, {1.0, {0.3, 0.4}}});
  for (auto& p : with.points) {
    p.velocities = {0.0, 0.0};
    p.num_velocities = 2;
  }
  rig.publish("trajectory/command", with);
  rig.cycle(1700);
  rig.publish("trajectory/command", trajectory_goal(10, {"tilt", "slide"}, {{0.5, {0.1, 0.1}}, {1.0, {0.0, 0.2}}}));
  rig.cycle(1700);
  ASSERT_EQ(result.messages.size(), 2u);
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::SUCCEEDED) << result.messages[0].message;
  EXPECT_EQ(result.messages[1].goal_id, 10);
  EXPECT_EQ(result.messages[1].status, trajectory_status_t::SUCCEEDED) << result.messages[1].message;
  EXPECT_NEAR(rig.actuator("slide_motor").position, 0.2, 1e-9);
}

// A goal taken in off the loop (the controller manager program's intake thread): decoded and planned on the intake's
// thread, taken whole by poll() between cycles, never before; the trajectory is the one the loop itself would have
// taken in that cycle, command for command, bit for bit.
TEST(ControllerManagerTrajectoryController, AGoalTakenInOffTheLoopIsTakenWholeAtPollAndFollowedAsInTheLoop) {
  cm::ManagerOptions off;
  off.intake_thread = true;
  Rig in_loop, off_loop(cm::builtin_registry(), lcm_control::testing::data("test_bot.urdf"),
                        lcm_control::testing::data("test_bot.yaml"), off);
  Recorder<trajectory_status_t> in_result(in_loop.bus.lcm(), "trajectory/result");
  Recorder<trajectory_status_t> off_result(off_loop.bus.lcm(), "trajectory/result");
  Recorder<trajectory_status_t> off_feedback(off_loop.bus.lcm(), "trajectory/feedback");
  for (Rig* r : {&in_loop, &off_loop}) {
    r->start("trajectory");
    r->cycle(10);
  }
  const joint_trajectory_t g =
      trajectory_goal(21, {"tilt", "slide"}, {{0.4, {0.2, 0.1}}, {0.8, {0.5, 0.3}}, {1.2, {0.3, 0.6}}, {1.5, {0.1, 0.2}}});
  in_loop.publish("trajectory/command", g);
  off_loop.publish("trajectory/command", g);
  for (int k = 0; k < 2000 && off_loop.cm->taking_in(); ++k) {
    if (k == 200) {  // planned, not taken: the loop still holds
      EXPECT_TRUE(off_loop.cm->taking_in());
      EXPECT_TRUE(off_feedback.messages.empty());
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (k >= 200) off_loop.cm->poll(monotonic_us());
  }
  EXPECT_FALSE(off_loop.cm->taking_in());
  in_loop.cycle(1800);
  off_loop.cycle(1800);
  ASSERT_EQ(in_result.messages.size(), 1u);
  ASSERT_EQ(off_result.messages.size(), 1u);
  EXPECT_EQ(off_result.messages[0].status, trajectory_status_t::SUCCEEDED) << off_result.messages[0].message;
  ASSERT_EQ(in_loop.commands.size(), off_loop.commands.size());
  for (size_t k = 0; k < in_loop.commands.size(); ++k)
    for (int a = 0; a < in_loop.commands[k].num_actuators; ++a)
      ASSERT_EQ(in_loop.commands[k].command[a], off_loop.commands[k].command[a]) << "cycle " << k << " actuator " << a;
}

// An effort PID's command holds -d*velocity (its D term from the measured velocity); the command says so, so that
// a simulator can apply that part implicitly (hardware_command_t::damping). Other commands hold none.
TEST(ControllerManagerPidControllers, EffortCommandsCarryTheDampingTheyHold) {
  Rig rig;
  auto damping_of = [&](const std::string& actuator) {
    const hardware_command_t& c = rig.commands.back();
    for (int a = 0; a < c.num_actuators; ++a)
      if (c.name[a] == actuator) return c.damping[a];
    ADD_FAILURE() << actuator;
    return -1.0;
  };
  rig.start("effort_trajectory");  // gains arm d 50, spin d 10
  rig.start("slide_position");
  rig.cycle(2);
  EXPECT_EQ(damping_of("arm_motor"), 50.0);
  EXPECT_EQ(damping_of("spin_motor"), 10.0);
  EXPECT_EQ(damping_of("slide_motor"), 0.0);  // a position command
  ASSERT_TRUE(rig.load("arm_position").ok);
  ASSERT_TRUE(rig.load("spin_velocity").ok);
  ASSERT_TRUE(rig.switch_({"arm_position", "spin_velocity"}, {"effort_trajectory"}).ok);
  rig.cycle(2);
  EXPECT_EQ(damping_of("arm_motor"), 50.0);  // effort_controllers/JointPositionController: pid d
  EXPECT_EQ(damping_of("spin_motor"), 5.0);  // effort_controllers/JointVelocityController: -p*velocity
  ASSERT_TRUE(rig.switch_({}, {"arm_position", "spin_velocity"}).ok);
  rig.cycle(1);
  EXPECT_EQ(damping_of("arm_motor"), 0.0);  // MODE_NONE
  EXPECT_EQ(damping_of("spin_motor"), 0.0);
}

TEST(ControllerManagerTrajectoryController, EffortVariantTracksWithItsGains) {
  Rig rig;
  Recorder<trajectory_status_t> result(rig.bus.lcm(), "effort_trajectory/result");
  auto& arm = rig.actuator("arm_motor");
  arm.gravity = 10.0;
  arm.inertia = 0.2;
  rig.actuator("spin_motor").inertia = 0.1;
  rig.start("effort_trajectory");
  rig.publish("effort_trajectory/command",
              trajectory_goal(8, {"arm", "spin"}, {{1.0, {0.5, 1.0}}, {2.0, {1.0, 3.0}}, {3.0, {0.8, 6.0}}}));
  rig.cycle(4500);
  ASSERT_EQ(result.messages.size(), 1u);
  EXPECT_EQ(result.messages[0].status, trajectory_status_t::SUCCEEDED) << result.messages[0].message;
  EXPECT_NEAR(rig.actuator("arm_motor").position, 0.8, 0.02);
}
