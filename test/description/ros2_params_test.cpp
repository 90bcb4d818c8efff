// The ROS 2 parameter file as the controllers file: controller_manager's
// update_rate and types, per-controller ros__parameters (type given there too),
// /** wildcards, namespaced node paths, dotted keys and $(var ...), each
// reproducing a trait of the real ROS 2 robots' YAML on the project's own files.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>

#include "description/control_config.hpp"
#include "description/robot_model.hpp"
#include "description/ros2_params.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

struct Read {
  std::string path;
  RobotModel model;
  std::string error;  // "" if it was read
};

Read read(const std::string& yaml, std::vector<std::pair<std::string, std::string>> args = {}, std::string ns = "") {
  Read r;
  r.path = lt::temp_dir("ros2_params") + "/controllers.yaml";
  std::ofstream(r.path) << yaml;
  r.model.options.args = std::move(args);
  r.model.ns = std::move(ns);
  try {
    load_control_config_into(r.model, {r.path});
  } catch (const ModelError& e) {
    r.error = e.what();
  }
  return r;
}

std::vector<std::string> names(const RobotModel& m) {
  std::vector<std::string> v;
  for (const auto& c : m.controllers) v.push_back(c.name);
  return v;
}

std::string lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += l + "\n";
  return s;
}

std::string dump(const YAML::Node& n) {
  YAML::Emitter e;
  e.SetMapFormat(YAML::Flow);
  e.SetSeqFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

}  // namespace

TEST(Ros2Params, TypeUnderControllerManagerAndInsideTheControllersOwnSection) {
  const Read r = read(R"(controller_manager:
  ros__parameters:
    update_rate: 1000  # Hz

    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster

arm_controller:
  ros__parameters:
    type: joint_trajectory_controller/JointTrajectoryController
    joints:
      - joint1
      - joint2
    command_interfaces: [position]
    state_interfaces: [position, velocity]
    constraints:
      goal_time: 0.0
      joint1: { trajectory: 0.2, goal: 0.1 }
)");
  ASSERT_EQ(r.error, "");
  const RobotModel& m = r.model;
  EXPECT_EQ(m.update_rate_hz, 1000.0);
  ASSERT_EQ(names(m), (std::vector<std::string>{"joint_state_broadcaster", "arm_controller"}));
  EXPECT_EQ(m.controllers[0].type, "joint_state_broadcaster/JointStateBroadcaster");
  EXPECT_EQ(dump(m.controllers[0].params), "{type: joint_state_broadcaster/JointStateBroadcaster}");
  EXPECT_EQ(m.controllers[1].type, "joint_trajectory_controller/JointTrajectoryController");
  EXPECT_EQ(dump(m.controllers[1].params),
            "{type: joint_trajectory_controller/JointTrajectoryController, joints: [joint1, joint2], "
            "command_interfaces: [position], state_interfaces: [position, velocity], constraints: {goal_time: 0.0, "
            "joint1: {trajectory: 0.2, goal: 0.1}}}");
  EXPECT_EQ(m.config_section, "");
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
  EXPECT_EQ(m.notes, std::vector<std::string>{fmt::format("{}: a ROS 2 parameter file: 2 controllers, controller_manager "
                                                          "update_rate 1000 Hz",
                                                          r.path)});
}

TEST(Ros2Params, UrStyleTypesDeclaredUnderControllerManagerWithSectionsBelow) {
  const Read r = read(R"(controller_manager:
  ros__parameters:
    update_rate: 500
    joint_state_broadcaster:
      type: joint_state_broadcaster/JointStateBroadcaster
    io_and_status_controller:
      type: ur_controllers/GPIOController
    forward_position_controller:
      type: position_controllers/JointGroupPositionController

forward_position_controller:
  ros__parameters:
    joints: [a, b]
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.model.update_rate_hz, 500.0);
  EXPECT_EQ(names(r.model),
            (std::vector<std::string>{"joint_state_broadcaster", "io_and_status_controller", "forward_position_controller"}));
  EXPECT_EQ(r.model.controllers[1].type, "ur_controllers/GPIOController");  // carried as written, vendor or not
  EXPECT_EQ(dump(r.model.controllers[2].params), "{type: position_controllers/JointGroupPositionController, joints: [a, b]}");
}

TEST(Ros2Params, NoControllerManagerSectionAndVarSubstitution) {
  const std::string yaml = R"(joint_state_broadcaster:
  ros__parameters:
    type: joint_state_broadcaster/JointStateBroadcaster
    update_rate: 50  # Hz

forward_position_controller:
  ros__parameters:
    type: forward_command_controller/ForwardCommandController
    joints:
      - $(var prefix)1
      - $(var prefix)2
    interface_name: position
)";
  const Read r = read(yaml, {{"prefix", "joint"}});
  ASSERT_EQ(r.error, "");
  EXPECT_FALSE(r.model.update_rate_hz);
  ASSERT_EQ(names(r.model), (std::vector<std::string>{"joint_state_broadcaster", "forward_position_controller"}));
  EXPECT_EQ(r.model.controllers[0].params["update_rate"].as<int>(), 50);  // a controller's own rate stays its param
  EXPECT_EQ(dump(r.model.controllers[1].params["joints"]), "[joint1, joint2]");

  const Read missing = read(yaml);
  EXPECT_EQ(missing.error, fmt::format("{}:10: $(var prefix) has no value; give its value with --arg prefix=VALUE "
                                       "(launch files: args: {{prefix: VALUE}}), as roslaunch does for <rosparam "
                                       "subst_value=\"true\"> (2 lines use it)",
                                       missing.path));
}

TEST(Ros2Params, WildcardSectionsMergeFirstThenTheSpecificOnes) {
  const Read r = read(R"(/**:
  controller_manager:
    ros__parameters:
      update_rate: 100
      base_controller:
        type: diff_drive_controller/DiffDriveController
  base_controller:
    ros__parameters:
      wheel_radius: 0.1
      limits: {max: 1.0, min: -1.0}
/**/base_controller:
  ros__parameters:
    wheel_separation: 0.5
base_controller:
  ros__parameters:
    wheel_radius: 0.3
    limits: {max: 2.0}
/**:
  ros__parameters:
    use_sim_time: true
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.model.update_rate_hz, 100.0);
  ASSERT_EQ(names(r.model), std::vector<std::string>{"base_controller"});
  EXPECT_EQ(dump(r.model.controllers[0].params),
            "{type: diff_drive_controller/DiffDriveController, wheel_radius: 0.3, limits: {max: 2.0, min: -1.0}, "
            "wheel_separation: 0.5, use_sim_time: true}");
}

TEST(Ros2Params, DottedKeysAreNestedMaps) {
  const Read r = read(R"(controller_manager:
  ros__parameters:
    update_rate: 100
    base_controller.type: diff_drive_controller/DiffDriveController
base_controller:
  ros__parameters:
    linear.x.has_velocity_limits: true
    linear.x.max_velocity: 1.0
    linear:
      x:
        min_velocity: -1.0
    angular.z.max_velocity: 2.0
    pose_covariance_diagonal : [0.001, 0.001]
)");
  ASSERT_EQ(r.error, "");
  ASSERT_EQ(names(r.model), std::vector<std::string>{"base_controller"});
  EXPECT_EQ(dump(r.model.controllers[0].params),
            "{type: diff_drive_controller/DiffDriveController, linear: {x: {has_velocity_limits: true, max_velocity: "
            "1.0, min_velocity: -1.0}}, angular: {z: {max_velocity: 2.0}}, pose_covariance_diagonal: [0.001, 0.001]}");
  EXPECT_EQ(r.model.controllers[0].params["linear"]["x"]["max_velocity"].as<double>(), 1.0);
}

TEST(Ros2Params, ANamespacedFileIsReadForItsOnlyNamespaceAndSaysSo) {
  const std::string yaml = R"(/rrbot_1/controller_manager:
  ros__parameters:
    update_rate: 10
    jsb:
      type: joint_state_broadcaster/JointStateBroadcaster
/rrbot_1/forward_position_controller:
  ros__parameters:
    type: forward_command_controller/ForwardCommandController
    joints: [rrbot_1_joint1]
)";
  const Read r = read(yaml);
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.model.config_section, "rrbot_1");
  EXPECT_EQ(names(r.model), (std::vector<std::string>{"jsb", "forward_position_controller"}));
  EXPECT_EQ(r.model.update_rate_hz, 10.0);
  EXPECT_EQ(r.model.notes.front(), fmt::format("{}: parameters read for namespace '/rrbot_1', the only one the file "
                                               "names (run with --namespace rrbot_1 to have its channels there too)",
                                               r.path));
  // Given the namespace, it is read there; another one finds nothing.
  EXPECT_EQ(names(read(yaml, {}, "rrbot_1").model).size(), 2u);
  EXPECT_TRUE(read(yaml, {}, "rrbot_2").model.controllers.empty());

  const Read two = read(yaml + "/rrbot_2/controller_manager:\n  ros__parameters:\n    update_rate: 10\n");
  EXPECT_EQ(two.error, fmt::format("{}: the nodes are in several namespaces (rrbot_1, rrbot_2); say which robot with "
                                   "--namespace NAME",
                                   two.path));
}

TEST(Ros2Params, UnknownEntriesAreWarnedAndIgnoredAsToday) {
  const Read r = read(R"(controller_manager:
  ros__parameters:
    update_rate: 100
    jsb:
      type: joint_state_broadcaster/JointStateBroadcaster
publisher_node:
  ros__parameters:
    goal_names: [pos1]
stray_setting: 3
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(names(r.model), std::vector<std::string>{"jsb"});
  EXPECT_EQ(r.model.warnings,
            (std::vector<std::string>{
                fmt::format("{}: top-level entry 'stray_setting' holds no ros__parameters (neither a controller nor "
                            "the controller_manager); it is ignored",
                            r.path),
                fmt::format("{}: 'publisher_node' is neither a controller (no type under controller_manager: "
                            "ros__parameters: publisher_node: nor in its own ros__parameters) nor the "
                            "controller_manager; it is ignored",
                            r.path)}));
}

TEST(Ros2Params, ConflictingTypesTakeTheControllerManagersAndWarn) {
  const Read r = read(R"(controller_manager:
  ros__parameters:
    arm:
      type: position_controllers/JointGroupPositionController
arm:
  ros__parameters:
    type: velocity_controllers/JointGroupVelocityController
)");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(r.model.controllers.at(0).type, "position_controllers/JointGroupPositionController");
  EXPECT_EQ(r.model.controllers.at(0).params["type"].as<std::string>(),
            "position_controllers/JointGroupPositionController");
  EXPECT_EQ(r.model.warnings, std::vector<std::string>{fmt::format(
                                  "{}: controller 'arm' has type 'position_controllers/JointGroupPositionController' "
                                  "under controller_manager and 'velocity_controllers/JointGroupVelocityController' in "
                                  "its own ros__parameters; using the controller_manager's, "
                                  "'position_controllers/JointGroupPositionController'",
                                  r.path)});
}

TEST(Ros2Params, BadValuesAreRefusedNamingTheKey) {
  const Read r = read(R"(controller_manager:
  ros__parameters:
    update_rate: fast
    arm:
      type: [a, b]
)");
  EXPECT_EQ(r.error,
            fmt::format("{0}: controller_manager/ros__parameters/update_rate: 'fast' is not a positive number (Hz)\n"
                        "{0}: controller_manager/ros__parameters/arm/type: expected a controller type name such as "
                        "joint_trajectory_controller/JointTrajectoryController",
                        r.path));
  const Read list = read("arm:\n  ros__parameters: [1, 2]\n");
  EXPECT_EQ(list.error, fmt::format("{}: arm/ros__parameters: expected a map of parameters", list.path));
}

TEST(Ros2Params, Ros1FilesAreNotTakenForRos2) {
  EXPECT_FALSE(is_ros2_parameter_file(YAML::Load("j1_controller: {type: effort_controllers/JointPositionController}")));
  EXPECT_FALSE(is_ros2_parameter_file(YAML::Load("rrbot: {joint_state_controller: {type: x}}")));
  EXPECT_TRUE(is_ros2_parameter_file(YAML::Load("controller_manager: {ros__parameters: {update_rate: 100}}")));
  EXPECT_TRUE(is_ros2_parameter_file(YAML::Load("/**: {arm: {ros__parameters: {type: x}}}")));
  const Read r = read("j1_controller:\n  type: effort_controllers/JointPositionController\n  joint: j1\n");
  ASSERT_EQ(r.error, "");
  EXPECT_EQ(names(r.model), std::vector<std::string>{"j1_controller"});
  EXPECT_FALSE(r.model.update_rate_hz);
  EXPECT_TRUE(r.model.notes.empty()) << lines(r.model.notes);
}

TEST(Ros2Params, NodePathMatchingFollowsRclcpp) {
  EXPECT_TRUE(node_path_matches("/**", "/controller_manager"));
  EXPECT_TRUE(node_path_matches("/**", "/ns/a/arm"));
  EXPECT_TRUE(node_path_matches("/**/arm", "/arm"));
  EXPECT_TRUE(node_path_matches("/**/arm", "/ns/a/arm"));
  EXPECT_FALSE(node_path_matches("/**/arm", "/ns/arm2"));
  EXPECT_TRUE(node_path_matches("arm", "/arm"));
  EXPECT_FALSE(node_path_matches("/arm", "/ns/arm"));
  EXPECT_TRUE(node_path_matches("/ns/arm", "/ns/arm"));
  EXPECT_TRUE(node_path_matches("/*/arm", "/ns/arm"));
  EXPECT_FALSE(node_path_matches("/*/arm", "/arm"));
}

TEST(Ros2Params, ExpandAndMergeHelpers) {
  EXPECT_EQ(dump(expand_dotted_keys(YAML::Load("{a.b: 1, a: {c: 2}, d: [x.y], e.: 3}"))),
            "{a: {b: 1, c: 2}, d: [x.y], e.: 3}");
  YAML::Node into = YAML::Load("{a: {b: 1, c: [1, 2]}, d: 4}");
  deep_merge(into, YAML::Load("{a: {c: [3], e: 5}, f: 6}"));
  EXPECT_EQ(dump(into), "{a: {b: 1, c: [3], e: 5}, d: 4, f: 6}");
}
