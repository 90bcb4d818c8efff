// The traits of robots people bring from ROS, on the project's own test robots
// (test/robots): UR's +-2*pi limits, rrbot's namespaced YAML, Franka's three
// transmissions per joint, vendor transmission types and $(arg) placeholders.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

std::string robot(const std::string& file) { return lt::source("test/robots/" + file); }

LoadOptions with_args(std::vector<std::pair<std::string, std::string>> args, std::string ns = "") {
  LoadOptions o;
  o.args = std::move(args);
  o.ns = std::move(ns);
  return o;
}

std::string lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += l + "\n";
  return s;
}

size_t count_containing(const std::vector<std::string>& v, const std::string& needle) {
  return size_t(std::count_if(v.begin(), v.end(), [&](const auto& l) { return l.find(needle) != std::string::npos; }));
}

}  // namespace

TEST(RealRobotTraits, UrLikeArmWithTwoPiLimitsLoadsWithoutAWord) {
  const RobotModel m = load_robot_model(robot("ur_like.urdf"), robot("ur_like.yaml"));
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
  EXPECT_TRUE(m.hints.empty()) << lines(m.hints);
  ASSERT_NE(m.joint("shoulder_pan_joint"), nullptr);
  EXPECT_DOUBLE_EQ(m.joint("shoulder_pan_joint")->upper - m.joint("shoulder_pan_joint")->lower, 4 * M_PI);
  ASSERT_EQ(m.controllers.size(), 3u);
  // The YAML's aliases (&robot_joints, *loop_hz) resolve as rosparam resolves them.
  EXPECT_EQ(m.controller("joint_group_eff_controller")->params["joints"].size(), 6u);
  EXPECT_EQ(m.controller("eff_joint_traj_controller")->params["state_publish_rate"].as<int>(), 125);
}

TEST(RealRobotTraits, NamespacedYamlIsReadUnderThePluginsRobotNamespace) {
  const RobotModel m = load_robot_model(robot("ns_bot.urdf"), robot("ns_bot.yaml"));
  EXPECT_EQ(m.ns, "ns_bot");
  EXPECT_EQ(m.config_section, "ns_bot");
  ASSERT_EQ(m.controllers.size(), 3u);
  EXPECT_EQ(m.controllers[1].name, "joint1_position_controller");
  EXPECT_EQ(count_containing(m.notes, "controllers read from 'ns_bot:', the robot's namespace"), 1u) << lines(m.notes);
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
}

TEST(RealRobotTraits, AnotherNamespaceStillFindsTheOnlyControllerMapAndSaysSo) {
  const RobotModel m = load_robot_model(robot("ns_bot.urdf"), robot("ns_bot.yaml"), with_args({}, "/lab/bot2/"));
  EXPECT_EQ(m.ns, "lab/bot2");
  EXPECT_EQ(m.config_section, "ns_bot");
  EXPECT_EQ(m.controllers.size(), 3u);
  EXPECT_EQ(count_containing(m.notes, "'ns_bot:'"), 1u) << lines(m.notes);
}

TEST(RealRobotTraits, ThreeTransmissionsPerJointAndAVendorTypeAreSkippedWithOneWarningEach) {
  const RobotModel m =
      load_robot_model(robot("multi_trans_arm.urdf"), robot("multi_trans_arm.yaml"), with_args({{"arm_id", "arm"}}));
  ASSERT_EQ(m.transmissions.size(), 3u);
  for (const auto& t : m.transmissions) {
    EXPECT_EQ(t.interfaces.front(), Interface::Position) << t.joint;
    EXPECT_EQ(t.skipped_interfaces, (std::vector<Interface>{Interface::Velocity, Interface::Effort})) << t.joint;
  }
  EXPECT_EQ(m.warnings.size(), 5u) << lines(m.warnings);
  EXPECT_EQ(count_containing(m.warnings, "transmission 'arm_vendor_state': skipped: type "
                                         "'vendor_hw/VendorStateInterface' is not supported"),
            1u)
      << lines(m.warnings);
  for (const char* j : {"arm_joint1", "arm_joint2", "arm_joint3"})
    EXPECT_EQ(count_containing(m.warnings, fmt::format("joint '{}' has 3 transmissions; the first", j)), 1u)
        << lines(m.warnings);
  EXPECT_EQ(count_containing(m.warnings, "the other 2 are skipped"), 3u) << lines(m.warnings);
  EXPECT_EQ(count_containing(m.warnings, "have no <mechanicalReduction>; using 1"), 1u) << lines(m.warnings);
  EXPECT_EQ(m.controller("position_joint_trajectory_controller")->params["joints"][1].as<std::string>(),
            "arm_joint2");
}

TEST(RealRobotTraits, AnArgPlaceholderWithoutAValueIsOneErrorNamingTheFix) {
  try {
    load_robot_model(robot("multi_trans_arm.urdf"), robot("multi_trans_arm.yaml"));
    FAIL() << "loaded with $(arg arm_id) unset";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    const std::string& p = e.problems()[0];
    EXPECT_NE(p.find("multi_trans_arm.yaml:7"), std::string::npos) << p;
    EXPECT_NE(p.find("arm_id"), std::string::npos) << p;
    EXPECT_NE(p.find("--arg arm_id=VALUE"), std::string::npos) << p;
  }
}

TEST(RealRobotTraits, ZeroEffortOnPositionJointsWithoutGainsIsOneWarningPerJoint) {
  // ROS-Industrial's arms: effort="0" everywhere, PositionJointInterface, no pid_gains (Gazebo sets the position).
  const RobotModel m = load_robot_model(robot("industrial_arm.urdf"), robot("industrial_arm.yaml"));
  EXPECT_EQ(count_containing(m.warnings, "<limit effort=\"0\"> ignored"), 2u) << lines(m.warnings);
  for (const char* j : {"joint_1", "joint_2"})
    EXPECT_EQ(count_containing(m.warnings, fmt::format("industrial_arm.urdf: joint '{}': <limit effort=\"0\">", j)),
              1u)
        << lines(m.warnings);
}

TEST(RealRobotTraits, ZeroEffortStaysAnErrorWhereTheEffortLimitIsUsed) {
  // With pid_gains the position interface drives the joint by effort; an effort interface always does.
  const std::string dir = lt::temp_dir("zero_effort");
  std::ifstream in(robot("industrial_arm.yaml"));
  std::ofstream(dir + "/gains.yaml") << std::string(std::istreambuf_iterator<char>(in), {})
                                     << "gazebo_ros_control:\n  pid_gains:\n    joint_2: {p: 100, d: 1}\n";
  try {
    load_robot_model(robot("industrial_arm.urdf"), dir + "/gains.yaml");
    FAIL() << "loaded a PID joint with effort 0";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_NE(e.problems()[0].find("joint 'joint_2': <limit effort=\"0\"> would freeze the joint (no force allowed: "
                                   "its pid_gains in " + dir + "/gains.yaml drive it by effort)"),
              std::string::npos)
        << e.what();
  }
  std::ifstream u(robot("industrial_arm.urdf"));
  std::string urdf(std::istreambuf_iterator<char>(u), {});
  const std::string position = "<joint name=\"joint_1\"><hardwareInterface>hardware_interface/PositionJointInterface";
  ASSERT_NE(urdf.find(position), std::string::npos);
  urdf.replace(urdf.find(position), position.size(),
               "<joint name=\"joint_1\"><hardwareInterface>hardware_interface/EffortJointInterface");
  std::ofstream(dir + "/effort.urdf") << urdf;
  try {
    load_robot_model(dir + "/effort.urdf", "");
    FAIL() << "loaded an effort joint with effort 0";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_NE(e.problems()[0].find("joint 'joint_1': <limit effort=\"0\"> would freeze the joint"), std::string::npos)
        << e.what();
  }
}

TEST(RealRobotTraits, TwoControllerYamlsMergeInOrderAndSayWhichKeyTheLaterOneReplaced) {
  // As a launch file's two <rosparam file=.../>: rosparam loads both into one namespace, the later key wins.
  const std::string a = robot("industrial_arm.yaml"), b = robot("industrial_arm_overrides.yaml");
  const RobotModel m = load_robot_model(robot("industrial_arm.urdf"), std::vector<std::string>{a, b});
  ASSERT_EQ(m.controllers.size(), 3u);
  EXPECT_EQ(m.controllers[2].name, "joint_1_controller");
  const YAML::Node arm = m.controller("arm_controller")->params;
  EXPECT_EQ(arm["constraints"]["goal_time"].as<double>(), 1.0);
  EXPECT_EQ(arm["joints"].size(), 2u);  // maps merge key by key: the first file's other keys stay
  EXPECT_EQ(m.config_path, a + " + " + b);
  EXPECT_EQ(m.controller("joint_state_controller")->file, a);
  EXPECT_EQ(m.controller("joint_1_controller")->file, b);
  EXPECT_EQ(m.controller("arm_controller")->file, a + " + " + b);
  EXPECT_EQ(m.config_file_of("arm_controller/constraints/goal_time"), b);
  EXPECT_EQ(m.config_file_of("arm_controller/joints"), a);
  EXPECT_EQ(count_containing(m.notes, "replaces"), 1u) << lines(m.notes);
  EXPECT_EQ(count_containing(m.notes, b + ": arm_controller/constraints/goal_time replaces the value from " + a), 1u)
      << lines(m.notes);
}

TEST(RealRobotTraits, AProblemInTheSecondControllerYamlNamesThatFile) {
  const std::string dir = lt::temp_dir("two_yamls");
  std::ofstream(dir + "/gains.yaml") << "gazebo_ros_control:\n  pid_gains:\n    no_such_joint: {p: 1}\n";
  try {
    load_robot_model(robot("industrial_arm.urdf"), std::vector<std::string>{robot("industrial_arm.yaml"),
                                                                             dir + "/gains.yaml"});
    FAIL() << "loaded pid_gains of a joint the URDF does not have";
  } catch (const ModelError& e) {
    ASSERT_EQ(e.problems().size(), 1u) << e.what();
    EXPECT_EQ(e.problems()[0].rfind(dir + "/gains.yaml: gazebo_ros_control/pid_gains/no_such_joint: joint "
                                    "'no_such_joint' is not in the URDF", 0),
              0u)
        << e.what();
  }
  std::ofstream(dir + "/broken.yaml") << "arm_controller: [\n";
  try {
    load_robot_model(robot("industrial_arm.urdf"), std::vector<std::string>{robot("industrial_arm.yaml"),
                                                                             dir + "/broken.yaml"});
    FAIL() << "loaded a malformed YAML";
  } catch (const ModelError& e) {
    EXPECT_EQ(e.problems()[0].rfind(dir + "/broken.yaml:", 0), 0u) << e.what();
  }
}
