// Controller types describe themselves (controller_type.hpp): a type nobody here knows is one file (this one) and one
// registration line, and doctor's checks, `cmctl list-types`, `cmctl list` (what the dashboard's command panel reads)
// and send-trajectory's check see it from its declaration alone; the built-in types' declarations give the ROS
// catalog's parameter names of before.
#include "controller_interface/controller_type.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "bus/messages.hpp"
#include "controller_interface/registry.hpp"
#include "controller_manager/services.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "tools/lib/clients/trajectory_goal.hpp"
#include "controllers/builtin.hpp"
#include "controller_manager/plugins.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::Recorder;
using lcm_control::testing::Rig;
using lcm_control::tools::trajectory_controller;

namespace {

// The new type's file: an effort per joint of `joints`, times `scale`.
class TinyEffort : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    for (const auto& n : p.strings("joints")) joints_.push_back(ctx.claim(n, Interface::Effort));
    scale_ = p.number("scale", 1.0);
    efforts_.assign(joints_.size(), 0.0);
    ctx.take_commands(true, joints_.size(), [this](const double* v) {
      for (size_t k = 0; k < efforts_.size(); ++k) efforts_[k] = v[k];
    });
  }
  void starting(const Time&) override { std::fill(efforts_.begin(), efforts_.end(), 0.0); }
  void update(const Time&, double) override {
    for (size_t k = 0; k < joints_.size(); ++k) joints_[k]->command = scale_ * efforts_[k];
  }

 private:
  std::vector<JointData*> joints_;
  std::vector<double> efforts_;
  double scale_ = 1;
};

ControllerType tiny_effort_controller() {
  ControllerTypeInfo t;
  t.name = "test_controllers/TinyEffortController";
  t.ros = RosVersion::Both;
  t.doc = "scale times the effort of each joint";
  t.claims = {Interface::Effort, {"joints"}, "", {}};
  t.command = {"float64_array_t", "command", CommandInfo::kOnePerJoint, "effort"};
  t.parameters = {
      {"joints", "strings", "", "joints", "joints", "the joints"},
      {"scale", "number", "1", "scale", "gain", "times the command"},
      {"ros_only", "bool", "", "ros_only", "", "what ROS's has and this one does not", false},
  };
  return {t, [](const std::string&) { return std::make_unique<TinyEffort>(); }};
}

Registry with_tiny() {
  Registry r;
  register_builtin(r);
  r.add(tiny_effort_controller());  // the one registration line
  return r;
}

bool has(const std::vector<std::string>& lines, const std::string& text) {
  return std::any_of(lines.begin(), lines.end(), [&](const std::string& l) { return l.find(text) != std::string::npos; });
}

}  // namespace

TEST(ControllerTypes, ANewTypeIsOneFileAndOneLineAndDoctorChecksItsParameters) {
  const Registry registry = with_tiny();
  Rig rig(registry, lcm_control::testing::data("test_bot.urdf"), lcm_control::testing::data("tiny_bot.yaml"));
  const auto checks = rig.cm->check_configured();
  const auto tiny = std::find_if(checks.begin(), checks.end(), [](const ControllerCheck& c) { return c.name == "tiny"; });
  ASSERT_NE(tiny, checks.end());
  EXPECT_EQ(tiny->outcome, ControllerCheck::Loads) << tiny->message;
  EXPECT_TRUE(has(tiny->notes, "tiny/scael: not a parameter of test_controllers/TinyEffortController; ignored (did "
                               "you mean 'scale'?)"))
      << ::testing::PrintToString(tiny->notes);
  EXPECT_TRUE(has(tiny->notes, "tiny/ros_only: known ROS parameter of test_controllers/TinyEffortController, not "
                               "supported yet; ignored"))
      << ::testing::PrintToString(tiny->notes);
  EXPECT_EQ(parameter_names(*registry.info("test_controllers/TinyEffortController")),
            (std::vector<std::string>{"joints", "scale", "gain", "ros_only"}));
}

TEST(ControllerTypes, ANewTypeIsListedWithWhatItTakes) {
  const Registry registry = with_tiny();
  Rig rig(registry, lcm_control::testing::data("test_bot.urdf"), lcm_control::testing::data("tiny_bot.yaml"));
  Services services(*rig.cm, rig.bus);
  Recorder<cm_response_t> responses(rig.bus.lcm(), "controller_manager/response");
  cm_request_t types = cm_request(cm_request_t::LIST_TYPES, {}, {}, {});
  types.request_id = 1;
  rig.publish("controller_manager/request", types);
  ASSERT_EQ(responses.messages.size(), 1u);
  EXPECT_EQ(responses.messages[0].num_types, static_cast<int32_t>(builtin_registry().types().size() + 1));
  const auto& listed_types = responses.messages[0].types;
  EXPECT_NE(std::find(listed_types.begin(), listed_types.end(), "test_controllers/TinyEffortController"),
            listed_types.end());

  for (const char* name : {"joint_state_controller", "tiny", "trajectory"}) ASSERT_TRUE(rig.load(name).ok) << name;
  ASSERT_TRUE(rig.switch_({"joint_state_controller", "tiny", "trajectory"}, {}).ok);
  const std::vector<controller_info_t> listed = rig.cm->list();
  ASSERT_EQ(listed.size(), 3u);
  const controller_info_t& jsc = listed[0];
  EXPECT_EQ(jsc.command_type, "");
  EXPECT_EQ(jsc.command_width, 0);
  EXPECT_EQ(jsc.publishes, (std::vector<std::string>{"joint_states"}));
  const controller_info_t& tiny = listed[1];
  EXPECT_EQ(tiny.hardware_interface, "EffortJointInterface");
  EXPECT_EQ(tiny.command_type, "float64_array_t");
  EXPECT_EQ(tiny.command_channel, "command");
  EXPECT_EQ(tiny.command_width, 2);
  EXPECT_EQ(tiny.command_quantity, "effort");
  EXPECT_EQ(tiny.num_publishes, 0);
  EXPECT_EQ(listed[2].command_type, "joint_trajectory_t");
  EXPECT_EQ(listed[2].command_width, 0);

  // send-trajectory's check: what takes joint_trajectory_t, whatever its type's name.
  EXPECT_EQ(trajectory_controller(listed, "trajectory").name, "trajectory");
  try {
    trajectory_controller(listed, "tiny");
    ADD_FAILURE() << "tiny taken for a trajectory controller";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "tiny takes float64_array_t on tiny/command; joint_trajectory_t was given: use "
                                     "turret-cmd tiny V1 V2");
  }
}

// What a controller claims in init() is held to its declaration: the joints its joint parameters name, on the
// declared interface; the manager refuses a controller whose claims its type does not declare, naming the claim.
TEST(ControllerTypes, ClaimsAreHeldToTheDeclaration) {
  const ControllerTypeInfo info = tiny_effort_controller().info;
  const YAML::Node params = YAML::Load("{joints: [arm, spin]}");
  Claim fine;
  fine.interface = Interface::Effort;
  fine.joints = {"arm", "spin"};
  fine.interfaces = {Interface::Effort, Interface::Effort};
  EXPECT_EQ(undeclared_claim(info, params, fine), "");
  Claim other_joint = fine;
  other_joint.joints = {"arm", "tilt"};
  EXPECT_EQ(undeclared_claim(info, params, other_joint),
            "it claims 'tilt' on EffortJointInterface, which no parameter its declaration names for claims (joints) "
            "gives");
  Claim other_interface = fine;
  other_interface.interfaces = {Interface::Effort, Interface::Velocity};
  EXPECT_EQ(undeclared_claim(info, params, other_interface),
            "it claims 'spin' on VelocityJointInterface, which its declaration says it claims on EffortJointInterface");
  ControllerTypeInfo bare;
  bare.name = "x/Bare";  // declares nothing: not checked
  EXPECT_EQ(undeclared_claim(bare, params, other_joint), "");

  // A type whose declaration says one interface and whose init() claims another is refused at load (and by doctor).
  Registry registry = with_tiny();
  ControllerType lying = tiny_effort_controller();
  lying.info.claims.interface = Interface::Velocity;
  registry.add(lying);
  Rig rig(registry, lcm_control::testing::data("test_bot.urdf"), lcm_control::testing::data("tiny_bot.yaml"));
  const Reply r = rig.load("tiny");
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.message.find("type 'test_controllers/TinyEffortController' does not do what it declares: it claims "
                           "'arm' on EffortJointInterface, which its declaration says it claims on "
                           "VelocityJointInterface"),
            std::string::npos)
      << r.message;
}

// Only a type that declares itself chainable may export reference interfaces (ros2_control's
// ChainableControllerInterface); the refusal says what to declare.
class Exporter : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    JointData* j = ctx.claim(ctx.params().string("joint"), Interface::Position);
    ctx.export_reference(j->name, {Interface::Position}, j);
  }
  void starting(const Time&) override {}
  void update(const Time&, double) override {}
};

TEST(ControllerTypes, OnlyATypeDeclaredChainableExportsReferenceInterfaces) {
  const std::string yaml = lcm_control::testing::temp_dir("exporter") + "/exporter.yaml";
  std::ofstream(yaml) << "exp: {type: test/Exporter, joint: tilt}\n";
  for (const bool chainable : {false, true}) {
    Registry registry;
    register_builtin(registry);
    ControllerType t;
    t.info.name = "test/Exporter";
    t.info.doc = "exports its joint";
    t.info.claims = {Interface::Position, {"joint"}, "", {}};
    t.info.chainable = chainable;
    t.factory = [](const std::string&) { return std::make_unique<Exporter>(); };
    registry.add(t);
    Rig rig(registry, lcm_control::testing::data("test_bot.urdf"), yaml);
    const Reply r = rig.load("exp");
    EXPECT_EQ(r.ok, chainable) << r.message;
    if (!chainable) {
      EXPECT_NE(r.message.find("controller 'exp': type 'test/Exporter' exports the reference interface 'exp/tilt' but "
                               "does not declare itself chainable: set `chainable` (and `references`) in its "
                               "ControllerTypeInfo"),
                std::string::npos)
          << r.message;
    }
  }
}

// A plugin's type declares itself as a built-in one does (docs/examples/my_controllers): its parameters name a
// misspelt key, list-types gives its declaration, the listing what it claims.
TEST(ControllerTypes, APluginTypeDeclaresItselfAsABuiltInOneDoes) {
  Registry registry;
  register_builtin(registry);
  const std::vector<std::string> lines = load_plugins(registry, {SINE_PLUGIN});
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find(": my_controllers/SineController"), std::string::npos) << lines[0];
  const ControllerTypeInfo* info = registry.info("my_controllers/SineController");
  ASSERT_NE(info, nullptr);
  EXPECT_EQ(parameter_names(*info), (std::vector<std::string>{"joint", "amplitude", "frequency", "center"}));
  Rig rig(registry, lcm_control::testing::data("test_bot.urdf"), lcm_control::testing::data("sine_bot.yaml"));
  const auto checks = rig.cm->check_configured();
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].outcome, ControllerCheck::Loads) << checks[0].message;
  EXPECT_TRUE(has(checks[0].notes, "sine/frequncy: not a parameter of my_controllers/SineController; ignored (did you "
                                   "mean 'frequency'?)"))
      << ::testing::PrintToString(checks[0].notes);
  EXPECT_EQ(rig.cm->type_doc("my_controllers/SineController"),
            "ROS 2: moves one joint along center + amplitude * sin(2 pi frequency t)");
  const Reply loaded = rig.load("sine");
  ASSERT_TRUE(loaded.ok) << loaded.message;
  const std::vector<controller_info_t> listed = rig.cm->list();
  ASSERT_EQ(listed.size(), 1u);
  EXPECT_EQ(listed[0].hardware_interface, "PositionJointInterface");
  EXPECT_EQ(listed[0].joints, (std::vector<std::string>{"tilt"}));
  EXPECT_FALSE(listed[0].chainable);
}

// The names each built-in type answers to as ROS parameters are the ROS catalog's lists of before the types
// described themselves, in the same order (the closest one is suggested for a misspelt key).
TEST(ControllerTypes, BuiltinDeclarationsGiveTheRosParameterNames) {
  const Registry& r = builtin_registry();
  auto names = [&](const std::string& type) {
    const ControllerTypeInfo* info = r.info(type);
    EXPECT_NE(info, nullptr) << type;
    return info ? parameter_names(*info) : std::vector<std::string>{};
  };
  using V = std::vector<std::string>;
  // publish_mimic_joints is ours (ROS's behaviour with false), after ROS's names.
  EXPECT_EQ(names("joint_state_controller/JointStateController"),
            (V{"publish_rate", "joints", "extra_joints", "publish_mimic_joints"}));
  for (const char* t : {"position_controllers/JointPositionController", "velocity_controllers/JointVelocityController",
                        "effort_controllers/JointEffortController"})
    EXPECT_EQ(names(t), V{"joint"}) << t;
  for (const char* t : {"position_controllers/JointGroupPositionController",
                        "velocity_controllers/JointGroupVelocityController",
                        "effort_controllers/JointGroupEffortController"})
    EXPECT_EQ(names(t), (V{"joints", "interface_name"})) << t;
  EXPECT_EQ(names("effort_controllers/JointGroupPositionController"), V{"joints"});
  EXPECT_EQ(names("forward_command_controller/ForwardCommandController"), (V{"joints", "interface_name"}));
  EXPECT_EQ(names("forward_command_controller/MultiInterfaceForwardCommandController"),
            (V{"joint", "interface_names"}));
  EXPECT_EQ(names("pid_controller/PidController"),
            (V{"dof_names", "command_interface", "reference_and_state_interfaces", "gains",
               "set_current_state_as_first_setpoint", "use_external_measured_states", "reference_and_state_dof_names"}));
  for (const char* t : {"effort_controllers/JointPositionController", "effort_controllers/JointVelocityController",
                        "velocity_controllers/JointPositionController"})
    EXPECT_EQ(names(t), (V{"joint", "pid"})) << t;
  const V trajectory = {"joints", "gains", "velocity_ff", "constraints", "state_publish_rate", "action_monitor_rate",
                        "stop_trajectory_duration", "allow_partial_joints_goal", "hold_trajectory_duration",
                        "command_interfaces", "state_interfaces", "open_loop_control", "interpolation_method",
                        "cmd_timeout", "interface_name", "allow_integration_in_goal_trajectories",
                        "allow_nonzero_velocity_at_trajectory_end", "interpolate_from_desired_state",
                        "set_last_command_interface_value_as_state_on_activation", "speed_scaling_topic_name"};
  for (const char* t : {"position_controllers/JointTrajectoryController",
                        "velocity_controllers/JointTrajectoryController", "effort_controllers/JointTrajectoryController"})
    EXPECT_EQ(names(t), trajectory) << t;
  EXPECT_EQ(names("diff_drive_controller/DiffDriveController"),
            (V{"left_wheel", "left_wheel_names", "right_wheel", "right_wheel_names", "wheel_separation", "wheel_radius",
               "wheel_separation_multiplier", "wheel_radius_multiplier", "left_wheel_radius_multiplier",
               "right_wheel_radius_multiplier", "publish_rate", "cmd_vel_timeout", "base_frame_id", "odom_frame_id",
               "enable_odom_tf", "wheels_per_side", "use_stamped_vel", "tf_frame_prefix_enable", "tf_frame_prefix",
               "position_feedback", "open_loop",
               "velocity_rolling_window_size", "linear", "angular", "pose_covariance_diagonal",
               "twist_covariance_diagonal", "allow_multiple_cmd_vel_publishers", "publish_cmd",
               "publish_limited_velocity", "publish_wheel_joint_controller_state", "estimate_velocity_from_position"}));
  // Every built-in type declares its command and, when it claims joints, the parameters that name them.
  for (const auto& t : r.types()) {
    const ControllerTypeInfo& info = *r.info(t);
    EXPECT_EQ(info.name, t);
    if (info.claims.interface || !info.claims.interface_param.empty()) {
      EXPECT_FALSE(info.claims.joint_params.empty()) << t;
      EXPECT_FALSE(info.command.type.empty()) << t;
    }
    for (const auto& p : info.parameters) EXPECT_FALSE(p.doc.empty()) << t << " " << p.name;
  }
}
