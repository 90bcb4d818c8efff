// ROS 2's pid_controller/PidController on ros2_bot.urdf's twist (an effort joint) on the simulated rig: it brings the
// joint to a position reference; bad command_interface, reference_and_state_interfaces and gain keys are refused
// naming the key.
#include <gtest/gtest.h>

#include <cmath>

#include "lcm_control/float64_array_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"

using namespace lcm_control;
using lcm_control::testing::data;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const char* kTwistPid =
    "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position, velocity], "
    "gains: {twist: {p: 50, d: 5}}}";

// ros2_bot with a `twist_pid` entry of pid_controller/PidController whose parameters are `section`.
RobotModel with_pid(const std::string& section) {
  RobotModel m = load_robot_model(data("ros2_bot.urdf"), data("ros2_bot.yaml"));
  YAML::Node params = YAML::Load(section);
  params["type"] = "pid_controller/PidController";
  m.controllers.push_back(ControllerSpec{"twist_pid", "pid_controller/PidController", params, "twist_pid.yaml"});
  return m;
}

struct PidRig : lcm_control::testing::Rig {
  explicit PidRig(const std::string& section = kTwistPid)
      : Rig(cm::builtin_registry(), data("ros2_bot.urdf"), data("ros2_bot.yaml")) {
    model = with_pid(section);
    cm = std::make_unique<cm::ControllerManager>(model, bus, cm::builtin_registry());
  }
  void reference(std::vector<double> v) {
    float64_array_t m{};
    m.data = v;
    m.size = static_cast<int32_t>(v.size());
    publish("twist_pid/command", m);
  }
};

std::string load_message(const std::string& section) {
  Bus bus("memq://", "");
  cm::ControllerManager manager(with_pid(section), bus, cm::builtin_registry());
  const cm::Reply r = manager.load("twist_pid");
  return (r.ok ? "ok: " : "refused: ") + r.message;
}

}  // namespace

TEST(Ros2PidController, EffortPidBringsTwistToThePositionReference) {
  PidRig rig;
  rig.start("twist_pid");
  const double start = rig.joint("twist").position;
  rig.cycle(50);  // the first set point is the state read on start: it holds
  EXPECT_NEAR(rig.joint("twist").position, start, 1e-3);
  rig.reference({0.8});
  rig.cycle(3000);
  EXPECT_NEAR(rig.joint("twist").position, 0.8, 0.01);
  EXPECT_NEAR(rig.joint("twist").velocity, 0.0, 0.05);
  EXPECT_EQ(rig.commands.back().mode[2], hardware_command_t::MODE_EFFORT);
  EXPECT_LE(std::abs(rig.commands.back().command[2]), 20.0);  // the URDF's effort limit

  // Its PID is the one the gains service changes.
  cm::Controller* c = nullptr;
  for (const auto& slot : rig.cm->loop().slots())
    if (slot->name == "twist_pid") c = slot->controller.get();
  ASSERT_NE(c, nullptr);
  EXPECT_EQ(c->pid_joints(), std::vector<std::string>{"twist"});
  ASSERT_NE(c->pid("twist"), nullptr);
  EXPECT_DOUBLE_EQ(c->pid("twist")->gains().p, 50.0);
  EXPECT_DOUBLE_EQ(c->pid("twist")->gains().d, 5.0);
  EXPECT_EQ(c->pid("elbow"), nullptr);
}

TEST(Ros2PidController, WithoutTheFirstSetpointItHoldsUntilAReferenceComesAndClampsToUClamp) {
  PidRig rig(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position], "
      "set_current_state_as_first_setpoint: false, gains: {twist: {p: 1000, u_clamp_max: 3, u_clamp_min: -3}}}");
  rig.start("twist_pid");
  rig.cycle(5);
  EXPECT_DOUBLE_EQ(rig.commands.back().command[2], 0.0);  // no reference: effort 0
  rig.reference({1.0});
  rig.cycle(2);
  EXPECT_DOUBLE_EQ(rig.commands.back().command[2], 3.0);  // p * error, clamped to u_clamp_max
}

TEST(Ros2PidController, AVelocityReferenceIsFollowedOnTheEffortInterface) {
  PidRig rig(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [velocity], "
      "gains: {twist: {p: 20, i: 10, i_clamp_max: 5, i_clamp_min: -5}}}");
  rig.start("twist_pid");
  rig.reference({1.0});
  rig.cycle(1500);
  EXPECT_NEAR(rig.joint("twist").velocity, 1.0, 0.02);
}

TEST(Ros2PidController, BadInterfacesAreRefusedNamingTheKeyAndTheValidValues) {
  const std::string command = load_message(
      "{dof_names: [twist], command_interface: torque, reference_and_state_interfaces: [position], "
      "gains: {twist: {p: 1}}}");
  EXPECT_TRUE(has(command, "refused: ")) << command;
  EXPECT_TRUE(has(command, "twist_pid/command_interface: 'torque' is not a joint command interface; use position, "
                           "velocity or effort"))
      << command;
  // As ROS 2: one or two of position, velocity and effort ([velocity, effort] in a gz demo), the second taken as the
  // first's derivative.
  for (const char* rs : {"[torque]", "[position, position]", "[position, velocity, acceleration]", "[]"}) {
    const bool own_words = std::string(rs) == "[torque]" || std::string(rs).find("acceleration") != std::string::npos;
    const std::string bad = load_message(
        std::string("{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: ") + rs +
        ", gains: {twist: {p: 1}}}");
    EXPECT_TRUE(has(bad, "refused: ")) << bad;
    EXPECT_TRUE(has(bad, "twist_pid/reference_and_state_interfaces: ")) << bad;
    if (own_words) {
      EXPECT_TRUE(has(bad, "give one or two different ones of position, velocity and effort")) << bad;
    }
  }
  const std::string external = load_message(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position], "
      "use_external_measured_states: true}");
  EXPECT_TRUE(has(external, "refused: ") && has(external, "use_external_measured_states")) << external;
  // The interface must be one the joint's <ros2_control> offers.
  const std::string wrong = load_message(
      "{dof_names: [twist], command_interface: position, reference_and_state_interfaces: [position]}");
  EXPECT_TRUE(has(wrong, "refused: ") && has(wrong, "twist")) << wrong;
}

TEST(Ros2PidController, GainKeysAreRos2sAndUnknownOnesAreRefused) {
  const std::string ok = load_message(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position, velocity], "
      "gains: {twist: {p: 1, i: 0.5, d: 0.1, i_clamp_max: 2, i_clamp_min: -2, u_clamp_max: 10, u_clamp_min: -10, "
      "feedforward_gain: 0, angle_wraparound: false, antiwindup_strategy: none, tracking_time_constant: 0, "
      "error_deadband: 1e-16, save_i_term: true, activate_state_publisher: false}}}");
  EXPECT_TRUE(has(ok, "ok: ")) << ok;
  EXPECT_TRUE(has(ok, "gains/twist: tracking_time_constant, error_deadband, save_i_term, activate_state_publisher: "
                      "known ROS 2 gain keys (control_toolbox), not supported yet; ignored"))
      << ok;
  const std::string typo = load_message(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position], "
      "gains: {twist: {p: 1, feedforward: 2}}}");
  EXPECT_TRUE(has(typo, "refused: ")) << typo;
  EXPECT_TRUE(has(typo, "gains/twist/feedforward: unknown key; valid keys are p, i, d,")) << typo;
  EXPECT_TRUE(has(typo, "feedforward_gain")) << typo;
  const std::string nan = load_message(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position], "
      "gains: {twist: {p: fast}}}");
  EXPECT_TRUE(has(nan, "refused: ") && has(nan, "gains/twist/p")) << nan;
  const std::string other = load_message(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position], "
      "gains: {elbow: {p: 1}}}");
  EXPECT_TRUE(has(other, "refused: ") && has(other, "gains/elbow: not one of dof_names (twist)")) << other;
  const std::string none = load_message(
      "{dof_names: [twist], command_interface: effort, reference_and_state_interfaces: [position]}");
  EXPECT_TRUE(has(none, "ok: ") && has(none, "every gain is 0")) << none;
}
