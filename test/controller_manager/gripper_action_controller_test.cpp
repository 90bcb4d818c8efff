// GripperActionController driven in-process through the real loop (memq:// bus, simulated actuators of
// test_bot.urdf, gripper_bot.yaml): goals that succeed, stall (ABORTED, or SUCCEEDED with allow_stalling), preempt
// and are rejected; the effort limit; its parameters and declaration; no allocation on the loop path.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "controller_interface/registry.hpp"
#include "lcm_control/gripper_command_t.hpp"
#include "lcm_control/gripper_status_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::data;
using lcm_control::testing::Recorder;
using lcm_control::testing::Rig;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

gripper_command_t goal(int64_t id, double position, double max_effort = 0) {
  gripper_command_t g{};
  g.goal_id = id;
  g.position = position;
  g.max_effort = max_effort;
  return g;
}

struct GripperRig : Rig {
  GripperRig() : Rig(builtin_registry(), data("test_bot.urdf"), data("gripper_bot.yaml")) {}
};

}  // namespace

TEST(GripperActionController, PositionGoalSucceedsWithinToleranceAndTheJointStaysThere) {
  GripperRig rig;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper/result");
  rig.start("gripper");
  rig.cycle(5);
  EXPECT_TRUE(result.messages.empty());
  rig.publish("gripper/command", goal(1, 0.4, 3.0));
  rig.cycle(20);
  ASSERT_EQ(result.messages.size(), 1u);
  const gripper_status_t& r = result.messages[0];
  EXPECT_EQ(r.goal_id, 1);
  EXPECT_EQ(r.status, gripper_status_t::SUCCEEDED) << r.message;
  EXPECT_TRUE(r.reached_goal);
  EXPECT_FALSE(r.stalled);
  EXPECT_EQ(r.joint, "slide");
  EXPECT_EQ(r.goal_position, 0.4);
  EXPECT_NEAR(r.position, 0.4, 0.002);
  EXPECT_EQ(r.max_effort, 3.0);  // reported: a position interface limits nothing
  EXPECT_TRUE(has(r.message, "goal 1 reached: position 0.4")) << r.message;
  rig.cycle(100);
  EXPECT_EQ(result.messages.size(), 1u);  // one result per goal
  EXPECT_NEAR(rig.actuator("slide_motor").position, 0.4, 1e-12);
}

TEST(GripperActionController, EffortGoalTracksThroughThePidWithFeedback) {
  GripperRig rig;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper_effort/result");
  Recorder<gripper_status_t> feedback(rig.bus.lcm(), "gripper_effort/feedback");
  rig.actuator("arm_motor").inertia = 0.2;
  rig.start("gripper_effort");
  rig.publish("gripper_effort/command", goal(7, 0.5));
  rig.cycle(3000);
  ASSERT_EQ(result.messages.size(), 1u);
  const gripper_status_t& r = result.messages[0];
  EXPECT_EQ(r.status, gripper_status_t::SUCCEEDED) << r.message;
  EXPECT_TRUE(r.reached_goal);
  EXPECT_NEAR(r.position, 0.5, 0.005);
  EXPECT_EQ(r.max_effort, 50.0);  // goal 0 and max_effort 0: the URDF's limit
  ASSERT_GE(feedback.messages.size(), 3u);
  for (const auto& f : feedback.messages) {
    EXPECT_EQ(f.goal_id, 7);
    EXPECT_EQ(f.status, gripper_status_t::ACTIVE);
    EXPECT_LE(std::abs(f.effort), 50.0);
  }
  EXPECT_GT(feedback.messages[1].utime - feedback.messages[0].utime, 19000);  // action_monitor_rate 50 Hz
  EXPECT_LT(feedback.messages[1].utime - feedback.messages[0].utime, 21000);
}

// Gravity holds the arm at sin(q) = 2 / 10 when the goal allows 2 N*m: it stalls short of 1.0.
TEST(GripperActionController, ATinyMaxEffortStallsAndTheGoalIsAbortedWithoutAllowStalling) {
  GripperRig rig;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper_effort/result");
  Recorder<gripper_status_t> feedback(rig.bus.lcm(), "gripper_effort/feedback");
  auto& arm = rig.actuator("arm_motor");
  arm.inertia = 0.2, arm.gravity = 10, arm.damping = 2;
  rig.start("gripper_effort");
  rig.publish("gripper_effort/command", goal(3, 1.0, 2.0));
  rig.cycle(4000);
  ASSERT_EQ(result.messages.size(), 1u);
  const gripper_status_t& r = result.messages[0];
  EXPECT_EQ(r.status, gripper_status_t::ABORTED) << r.message;
  EXPECT_TRUE(r.stalled);
  EXPECT_FALSE(r.reached_goal);
  EXPECT_NEAR(r.position, std::asin(0.2), 0.01);
  EXPECT_NEAR(r.effort, 2.0, 1e-9);
  EXPECT_EQ(r.max_effort, 2.0);
  EXPECT_TRUE(has(r.message, "stalled at 0.2")) << r.message;
  EXPECT_TRUE(has(r.message, "set allow_stalling: true")) << r.message;
  for (const auto& f : feedback.messages) EXPECT_LE(std::abs(f.effort), 2.0 + 1e-12);
  EXPECT_NEAR(rig.actuator("arm_motor").position, std::asin(0.2), 0.01);  // still squeezing
}

TEST(GripperActionController, AStallIsASuccessWithAllowStallingAndTheControllersMaxEffort) {
  GripperRig rig;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper_effort_grasp/result");
  auto& arm = rig.actuator("arm_motor");
  arm.inertia = 0.2, arm.gravity = 10, arm.damping = 2;
  rig.start("gripper_effort_grasp");
  rig.publish("gripper_effort_grasp/command", goal(4, 1.0));  // max_effort 0: the controller's (2)
  rig.cycle(4000);
  ASSERT_EQ(result.messages.size(), 1u);
  const gripper_status_t& r = result.messages[0];
  EXPECT_EQ(r.status, gripper_status_t::SUCCEEDED) << r.message;
  EXPECT_TRUE(r.stalled);
  EXPECT_FALSE(r.reached_goal);
  EXPECT_EQ(r.max_effort, 2.0);
  EXPECT_NEAR(r.position, std::asin(0.2), 0.01);
  EXPECT_TRUE(has(r.message, "allow_stalling: succeeded")) << r.message;
}

TEST(GripperActionController, ANewGoalPreemptsAndStoppingPreempts) {
  GripperRig rig;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper_effort/result");
  rig.actuator("arm_motor").inertia = 0.2;
  rig.start("gripper_effort");
  rig.publish("gripper_effort/command", goal(1, 1.0));
  rig.cycle(10);
  rig.publish("gripper_effort/command", goal(2, -1.0));
  ASSERT_EQ(result.messages.size(), 1u);
  EXPECT_EQ(result.messages[0].goal_id, 1);
  EXPECT_EQ(result.messages[0].status, gripper_status_t::PREEMPTED);
  EXPECT_EQ(result.messages[0].message, "replaced by goal 2");
  rig.cycle(10);
  ASSERT_TRUE(rig.switch_({}, {"gripper_effort"}).ok);
  ASSERT_EQ(result.messages.size(), 2u);
  EXPECT_EQ(result.messages[1].goal_id, 2);
  EXPECT_EQ(result.messages[1].status, gripper_status_t::PREEMPTED);
  EXPECT_EQ(result.messages[1].message, "controller stopped");
}

TEST(GripperActionController, BadGoalsAreRejectedNamingTheJointAndItsLimits) {
  GripperRig rig;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper/result");
  rig.cycle();
  ASSERT_TRUE(rig.load("gripper").ok);
  rig.publish("gripper/command", goal(1, 0.5));
  ASSERT_EQ(result.messages.size(), 1u);
  EXPECT_EQ(result.messages[0].status, gripper_status_t::REJECTED);
  EXPECT_EQ(result.messages[0].message,
            "gripper: goal 1 rejected: the controller is not running (start it: cmctl start gripper)");
  ASSERT_TRUE(rig.switch_({"gripper"}, {}).ok);
  rig.publish("gripper/command", goal(2, 1.5));
  rig.publish("gripper/command", goal(3, NAN));
  ASSERT_EQ(result.messages.size(), 3u);
  EXPECT_EQ(result.messages[1].message,
            "gripper: goal 2 rejected: position 1.5 is outside the limits [0, 1] of joint 'slide' (URDF)");
  EXPECT_TRUE(has(result.messages[2].message, "gripper: goal 3 rejected: position nan or max_effort 0 is NaN/Inf"))
      << result.messages[2].message;
  for (const auto& m : result.messages) EXPECT_EQ(m.status, gripper_status_t::REJECTED);
  rig.cycle(10);
  EXPECT_NEAR(rig.actuator("slide_motor").position, 0.0, 1e-12);  // holds where it started
}

TEST(GripperActionController, ParametersAreCheckedAndRosOnesNoted) {
  GripperRig rig;
  rig.cycle();
  Reply r = rig.load("no_gains");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "no_gains/gains/arm: missing (required for EffortJointInterface): gains: {arm: {p, i, "
                             "d, i_clamp}}"))
      << r.message;
  r = rig.load("parallel_no_velocity");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "state_interfaces")) << r.message;
  EXPECT_TRUE(has(r.message, "must include velocity")) << r.message;
  r = rig.load("wrong_interface");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "needs EffortJointInterface on joint 'slide'")) << r.message;

  const auto checks = rig.cm->check_configured();
  const auto parallel =
      std::find_if(checks.begin(), checks.end(), [](const ControllerCheck& c) { return c.name == "parallel_gripper"; });
  ASSERT_NE(parallel, checks.end());
  EXPECT_EQ(parallel->outcome, ControllerCheck::Loads) << parallel->message;
  const auto noted = [&](const std::string& text) {
    return std::any_of(parallel->notes.begin(), parallel->notes.end(),
                       [&](const std::string& n) { return has(n, text); });
  };
  EXPECT_TRUE(noted("parallel_gripper/max_velocity: known ROS parameter")) << ::testing::PrintToString(parallel->notes);
  EXPECT_TRUE(noted("parallel_gripper/max_effort: 10 limits nothing on PositionJointInterface"))
      << ::testing::PrintToString(parallel->notes);
}

TEST(GripperActionController, DeclaresItsTypesCommandAndParameters) {
  const Registry& r = builtin_registry();
  for (const char* t : {"position_controllers/GripperActionController", "effort_controllers/GripperActionController",
                        "parallel_gripper_action_controller/GripperActionController"}) {
    const ControllerTypeInfo* info = r.info(t);
    ASSERT_NE(info, nullptr) << t;
    EXPECT_NE(info->ros, RosVersion::Ros1) << t;
    EXPECT_EQ(info->command.type, "gripper_command_t");
    EXPECT_EQ(info->command.channel, "command");
    EXPECT_EQ(info->claims.joint_params, std::vector<std::string>{"joint"});
  }
  EXPECT_EQ(r.info("effort_controllers/GripperActionController")->claims.interface, Interface::Effort);
  const auto names = parameter_names(*r.info("parallel_gripper_action_controller/GripperActionController"));
  for (const char* p : {"joint", "goal_tolerance", "max_effort", "allow_stalling", "stall_velocity_threshold",
                        "stall_timeout", "action_monitor_rate", "state_interfaces", "max_effort_interface",
                        "max_velocity", "max_velocity_interface"})
    EXPECT_NE(std::find(names.begin(), names.end(), p), names.end()) << p;

  GripperRig rig;
  rig.start("gripper_effort");
  const std::vector<controller_info_t> listed = rig.cm->list();
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].command_type, "gripper_command_t");
  EXPECT_EQ(listed[0].command_width, 0);
  EXPECT_EQ(listed[0].hardware_interface, "EffortJointInterface");
}

TEST(GripperActionController, TheLoopPathDoesNotAllocate) {
  GripperRig rig;
  rig.actuator("arm_motor").inertia = 0.2;
  Recorder<gripper_status_t> result(rig.bus.lcm(), "gripper_effort/result");
  rig.start("gripper_effort");
  rig.publish("gripper_effort/command", goal(1, 0.3));
  rig.cycle(2);
  EXPECT_EQ(rig.allocations_in_cycles(1500, true, false), 0);  // feedback, then the result
  rig.pump();
  ASSERT_EQ(result.messages.size(), 1u);  // the goal did finish inside the counted cycles
  EXPECT_EQ(result.messages[0].status, gripper_status_t::SUCCEEDED) << result.messages[0].message;
}
