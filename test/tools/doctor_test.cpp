// doctor on robots as people bring them: it exits 0 only when controller_manager
// would load the configured controllers, says which do not load and why, and
// names ignored parameters as ROS ones not supported yet or as typos.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "test/support/process.hpp"

namespace lt = lcm_control::testing;

namespace {

struct DoctorRun {
  int rc;
  std::string out;
};

DoctorRun doctor(std::vector<std::string> args) {
  args.insert(args.begin(), lt::bin("doctor"));
  lt::ChildProcess p(args);
  const int rc = p.wait(30);
  return {rc, p.output()};
}

std::string robot(const std::string& file) { return lt::source("test/robots/" + file); }

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

}  // namespace

TEST(Doctor, AnArmWhoseControllersAllLoadIsOk) {
  const DoctorRun r = doctor({"--urdf", robot("ur_like.urdf"), "--config", robot("ur_like.yaml")});
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_TRUE(has(r.out, "controller check (as controller_manager would load them):")) << r.out;
  EXPECT_TRUE(has(r.out, "eff_joint_traj_controller        loads")) << r.out;
  EXPECT_TRUE(has(r.out, "OK: 7 joints, 6 transmissions, 3 controllers\n")) << r.out;
}

TEST(Doctor, ControllersTheTransmissionsCannotTakeAreWarningsNamingTheSkippedTransmission) {
  const DoctorRun r = doctor(
      {"--urdf", robot("multi_trans_arm.urdf"), "--config", robot("multi_trans_arm.yaml"), "--arg", "arm_id=arm"});
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_TRUE(has(r.out, "effort_joint_trajectory_controller will not load with this URDF's transmissions")) << r.out;
  EXPECT_TRUE(has(r.out, "the joint's transmission with EffortJointInterface is skipped")) << r.out;
  EXPECT_TRUE(has(r.out, "(3 load with this URDF, 1 does not: see the warnings)")) << r.out;
}

TEST(Doctor, NoControllerInTheYamlIsAnError) {
  const std::string dir = lt::temp_dir("doctor_empty");
  std::ofstream(dir + "/other_robot.yaml") << "other_robot:\n  gazebo_ros_control:\n    pid_gains: {}\n";
  const DoctorRun r = doctor({"--urdf", robot("ns_bot.urdf"), "--config", dir + "/other_robot.yaml"});
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_TRUE(has(r.out, "other_robot.yaml: no controllers found (a controller is a map with a `type:` key, at the "
                         "top level or under the robot's namespace 'ns_bot:')"))
      << r.out;
}

TEST(Doctor, ARefusedControllerFailsAndIgnoredParametersAreNamedForWhatTheyAre) {
  const std::string dir = lt::temp_dir("doctor_params");
  std::ofstream(dir + "/arm.yaml") << R"(arm_controller:
  type: effort_controllers/JointTrajectoryController
  joints: [shoulder_pan_joint]
  gains: {shoulder_pan_joint: {p: 100, d: 10}}
  hold_trajectory_duration: 0.5
  state_publish_rat: 25
broken_controller:
  type: position_controllers/JointGroupPositionController
  joints: [no_such_joint]
)";
  const DoctorRun r = doctor({"--urdf", robot("ur_like.urdf"), "--config", dir + "/arm.yaml"});
  EXPECT_EQ(r.rc, 3) << r.out;
  EXPECT_TRUE(has(r.out, "arm_controller/hold_trajectory_duration: known ROS parameter of "
                         "effort_controllers/JointTrajectoryController, not supported yet; ignored"))
      << r.out;
  EXPECT_TRUE(has(r.out, "arm_controller/state_publish_rat: not a parameter of "
                         "effort_controllers/JointTrajectoryController; ignored (did you mean 'state_publish_rate'?)"))
      << r.out;
  EXPECT_TRUE(has(r.out, "no_such_joint")) << r.out;
}

TEST(Doctor, ZeroEffortOnADirectPositionJointIsOneWarningNotAnError) {
  const DoctorRun r = doctor({"--urdf", robot("industrial_arm.urdf"), "--config", robot("industrial_arm.yaml")});
  EXPECT_EQ(r.rc, 0) << r.out;
  for (const char* j : {"joint_1", "joint_2"}) {
    const std::string w = std::string("industrial_arm.urdf: joint '") + j + "': <limit effort=\"0\"> ignored";
    const size_t at = r.out.find(w);
    EXPECT_NE(at, std::string::npos) << r.out;
    EXPECT_EQ(r.out.find(w, at + 1), std::string::npos) << "said twice:\n" << r.out;
  }
}

TEST(Doctor, SeveralConfigsMergeAndAKeyIsBlamedOnTheFileItCameFrom) {
  const std::string dir = lt::temp_dir("doctor_configs");
  std::ofstream(dir + "/typo.yaml") << "arm_controller:\n  state_publish_rat: 25\n";
  const std::string a = robot("industrial_arm.yaml"), b = robot("industrial_arm_overrides.yaml");
  const DoctorRun r =
      doctor({"--urdf", robot("industrial_arm.urdf"), "--config", a, "--config", b, "--config", dir + "/typo.yaml"});
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_TRUE(has(r.out, "note: " + b + ": arm_controller/constraints/goal_time replaces the value from " + a)) << r.out;
  EXPECT_TRUE(has(r.out, "joint_1_controller               loads")) << r.out;
  EXPECT_TRUE(has(r.out, dir + "/typo.yaml: arm_controller/state_publish_rat: not a parameter of")) << r.out;
  EXPECT_TRUE(has(r.out, "OK: 3 joints, 2 transmissions, 3 controllers\n")) << r.out;
}

// The ROS 2 way: the YAML comes through the gz plugin's <parameters>, not --config. doctor checks it as launch would
// load it: a misspelt `joints:` fails here as it does with --config.
TEST(Doctor, TheYamlOfTheGzPluginsParametersIsCheckedAsLaunchLoadsIt) {
  const std::string dir = lt::temp_dir("doctor_plugin_yaml");
  std::ifstream urdf_in(robot("two_component_arm.urdf")), yaml_in(robot("two_component_arm.yaml"));
  std::stringstream urdf, yaml;
  urdf << urdf_in.rdbuf();
  yaml << yaml_in.rdbuf();
  std::ofstream(dir + "/two_component_arm.urdf") << urdf.str();
  std::ofstream(dir + "/two_component_arm.yaml") << yaml.str();
  const DoctorRun ok = doctor({"--urdf", dir + "/two_component_arm.urdf"});
  EXPECT_EQ(ok.rc, 0) << ok.out;
  EXPECT_TRUE(has(ok.out, "arm_controller                   loads")) << ok.out;

  std::string broken = yaml.str();
  const size_t at = broken.find("    joints: [shoulder, elbow]");
  ASSERT_NE(at, std::string::npos);
  broken.replace(at, 11, "    joint: ");
  std::ofstream(dir + "/two_component_arm.yaml") << broken;
  const DoctorRun bad = doctor({"--urdf", dir + "/two_component_arm.urdf"});
  EXPECT_EQ(bad.rc, 3) << bad.out;
  EXPECT_TRUE(has(bad.out, "arm_controller/joints: missing (required): a list of joint names; the file has 'joint': "
                           "did you mean 'joints'?"))
      << bad.out;
}

// doctor FILE checks what `launch FILE` would start, as launch resolves it: the launch file's robot, its YAML files
// merged, its controllers, its <arg>s with NAME:=VALUE over them. A broken key fails here, not after launch started.
TEST(Doctor, ALaunchFileIsCheckedAsLaunchWouldStartIt) {
  const std::string dir = lt::temp_dir("doctor_launch_file");
  std::ifstream yaml_in(lt::source("config/turret_bot.yaml"));
  std::stringstream yaml;
  yaml << yaml_in.rdbuf();
  std::ofstream(dir + "/bot.yaml") << yaml.str();
  std::ofstream(dir + "/bot.launch.yaml") << "urdf: " << lt::source("config/turret_bot.urdf")
                                          << "\nconfig: bot.yaml\ncontrollers: [joint_state_controller, j2_controller]\n";
  const DoctorRun ok = doctor({dir + "/bot.launch.yaml"});
  EXPECT_EQ(ok.rc, 0) << ok.out;
  EXPECT_TRUE(has(ok.out, "controllers joint_state_controller, j2_controller")) << ok.out;
  EXPECT_TRUE(has(ok.out, "OK: ")) << ok.out;

  std::string broken = yaml.str();
  const size_t at = broken.find("joint: j2");
  ASSERT_NE(at, std::string::npos) << broken;
  broken.replace(at, 9, "jont: j2");
  std::ofstream(dir + "/bot.yaml") << broken;
  const DoctorRun bad = doctor({dir + "/bot.launch.yaml"});
  EXPECT_EQ(bad.rc, 3) << bad.out;
  EXPECT_TRUE(has(bad.out, "j2_controller/joint: missing (required); the file has 'jont': did you mean 'joint'?"))
      << bad.out;

  // A controller the launch file starts that its YAML does not configure is named with the file that starts it.
  std::ofstream(dir + "/bot.yaml") << yaml.str();
  std::ofstream(dir + "/bot.launch.yaml") << "urdf: " << lt::source("config/turret_bot.urdf")
                                          << "\nconfig: bot.yaml\ncontrollers: [joint_state_controller, j3_controller]\n";
  const DoctorRun missing = doctor({dir + "/bot.launch.yaml"});
  EXPECT_EQ(missing.rc, 3) << missing.out;
  EXPECT_TRUE(has(missing.out, "bot.launch.yaml j3_controller: ")) << missing.out;
  EXPECT_TRUE(has(missing.out, "configures no controller 'j3_controller'")) << missing.out;

  // Both ways at once is a usage error.
  EXPECT_EQ(doctor({dir + "/bot.launch.yaml", "--urdf", lt::source("config/turret_bot.urdf")}).rc, 2);
}

// A ROS launch file with its <arg>s: NAME:=VALUE after the file replaces a default, as roslaunch's command line does.
TEST(Doctor, ARosLaunchFilesArgumentsReachTheFilesItChecks) {
  const std::string pkgs = lt::source("test");  // package `robots` is test/robots
  const DoctorRun ok = doctor({robot("industrial_arm.launch"), "--package-path", pkgs});
  EXPECT_EQ(ok.rc, 0) << ok.out;
  EXPECT_TRUE(has(ok.out, "controllers joint_state_controller, arm_controller")) << ok.out;

  const std::string dir = lt::temp_dir("doctor_ros_launch");
  std::ofstream(dir + "/overrides.yaml") << "arm_controller:\n  type: position_controllers/JointTrajectoryControler\n";
  const DoctorRun bad = doctor({robot("industrial_arm.launch"), "overrides:=" + dir + "/overrides.yaml",
                                "--package-path", pkgs});
  EXPECT_EQ(bad.rc, 3) << bad.out;
  EXPECT_TRUE(has(bad.out, "JointTrajectoryControler")) << bad.out;
  EXPECT_TRUE(has(bad.out, "position_controllers/JointTrajectoryController")) << bad.out;  // the one meant
}
