// Every user-caused input problem the robot model reports: one line, naming
// the file and the culprit. doctor turns them into a non-zero exit.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string p = dir + "/" + name;
  std::ofstream(p) << text;
  return p;
}

// A URDF of the source tree with `from` replaced by `to` (exactly once).
std::string urdf_with(const std::string& file, const std::string& from, const std::string& to) {
  std::string s = slurp(lt::source(file));
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << from << "' not in " << file;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}
std::string turret_urdf_with(const std::string& from, const std::string& to) {
  return urdf_with("config/turret_bot.urdf", from, to);
}

// Loads and returns the error text ("" if it loaded).
std::string load_error(const std::string& urdf_text, const std::string& yaml_text, std::string* urdf_path = nullptr) {
  const std::string dir = lt::temp_dir("validation");
  const std::string u = write(dir, "robot.urdf", urdf_text);
  const std::string y = write(dir, "robot.yaml", yaml_text);
  if (urdf_path) *urdf_path = u;
  try {
    load_robot_model(u, y);
  } catch (const ModelError& e) {
    EXPECT_FALSE(e.problems().empty());
    for (const auto& p : e.problems()) EXPECT_EQ(p.find('\n'), std::string::npos) << "one line per problem: " << p;
    return e.what();
  }
  return "";
}

const std::string kYaml = slurp(lt::source("config/turret_bot.yaml"));

}  // namespace

TEST(Validation, ZeroReduction) {
  std::string path;
  const auto e = load_error(
      turret_urdf_with("<mechanicalReduction>1</mechanicalReduction>", "<mechanicalReduction>0</mechanicalReduction>"),
      kYaml, &path);
  EXPECT_NE(e.find(path), std::string::npos) << e;
  EXPECT_NE(e.find("transmission 't1'"), std::string::npos) << e;
  EXPECT_NE(e.find("actuator 'a1'"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot be zero"), std::string::npos) << e;
}

TEST(Validation, TransmissionNamesAJointNotInTheUrdf) {
  const auto e = load_error(turret_urdf_with("<joint name=\"j2\">\n      <hardwareInterface>",
                                             "<joint name=\"j9\">\n      <hardwareInterface>"),
                            kYaml);
  EXPECT_NE(e.find("transmission 't2' names joint 'j9', which is not in the URDF (moving joints: j1, j2)"),
            std::string::npos)
      << e;
}

TEST(Validation, UnknownHardwareInterface) {
  const auto e = load_error(turret_urdf_with("hardware_interface/PositionJointInterface</hardwareInterface>\n    </joint>\n    <actuator name=\"a2\">",
                                             "hardware_interface/PositionInterface</hardwareInterface>\n    </joint>\n    <actuator name=\"a2\">"),
                            kYaml);
  EXPECT_NE(e.find("transmission 't2'"), std::string::npos) << e;
  EXPECT_NE(e.find("joint 'j2': unknown hardwareInterface 'hardware_interface/PositionInterface'"), std::string::npos)
      << e;
  EXPECT_NE(e.find("PositionJointInterface, VelocityJointInterface or EffortJointInterface"), std::string::npos) << e;
}

TEST(Validation, InterfaceWithoutPrefixIsAccepted) {
  const auto e = load_error(turret_urdf_with("hardware_interface/PositionJointInterface", "PositionJointInterface"), kYaml);
  EXPECT_EQ(e, "");
}

TEST(Validation, RevoluteLowerNotBelowUpper) {
  const auto e = load_error(turret_urdf_with("lower=\"-3.14\" upper=\"3.14\"", "lower=\"1\" upper=\"1\""), kYaml);
  EXPECT_NE(e.find("joint 'j2': limit lower 1 >= upper 1"), std::string::npos) << e;
}

TEST(Validation, MultiTurnRevoluteLimitsAreAccepted) {
  // Universal Robots ship +-2*pi on five of six joints; the position does not wrap, so the limits are valid.
  const std::string dir = lt::temp_dir("validation");
  const std::string u = write(dir, "robot.urdf",
                              turret_urdf_with("lower=\"-3.14\" upper=\"3.14\"",
                                               "lower=\"-6.283185307179586\" upper=\"6.283185307179586\""));
  const RobotModel m = load_robot_model(u, write(dir, "robot.yaml", kYaml));
  EXPECT_DOUBLE_EQ(m.joint("j2")->lower, -6.283185307179586);
  EXPECT_DOUBLE_EQ(m.joint("j2")->upper, 6.283185307179586);
  EXPECT_TRUE(m.hints.empty()) << m.hints.front();
  for (const auto& w : m.warnings) EXPECT_EQ(w.find("limit"), std::string::npos) << w;
}

TEST(Validation, OneTurnLimitsAreAHintNeverAnError) {
  // turret_bot's j2 (+-3.14): the tutorial's "strange at +-3.14" note, as a doctor hint.
  const RobotModel m = load_robot_model(lt::source("config/turret_bot.urdf"), lt::source("config/turret_bot.yaml"));
  ASSERT_EQ(m.hints.size(), 1u);
  EXPECT_NE(m.hints[0].find("joint 'j2': limits [-3.14, 3.14] span one full turn"), std::string::npos) << m.hints[0];
  EXPECT_NE(m.hints[0].find("continuous"), std::string::npos) << m.hints[0];
}

TEST(Validation, ZeroEffortLimit) {
  const auto e = load_error(turret_urdf_with("upper=\"1\" effort=\"1000\"", "upper=\"1\" effort=\"0\""), kYaml);
  EXPECT_NE(e.find("joint 'j1': <limit effort=\"0\"> would freeze the joint"), std::string::npos) << e;
}

TEST(Validation, ZeroVelocityLimit) {
  const auto e = load_error(turret_urdf_with("upper=\"3.14\" effort=\"1000\" velocity=\"50\"",
                                             "upper=\"3.14\" effort=\"1000\" velocity=\"0\""),
                            kYaml);
  EXPECT_NE(e.find("joint 'j2': <limit velocity=\"0\"> would freeze the joint"), std::string::npos) << e;
}

TEST(Validation, UnknownTopLevelYamlEntryIsWarnedByName) {
  const std::string dir = lt::temp_dir("validation");
  const std::string y = write(dir, "c.yaml", kYaml + "j3_controler:\n  joint: j2\nsome_setting: 3\n");
  const RobotModel m = load_robot_model(lt::source("config/turret_bot.urdf"), y);
  ASSERT_EQ(m.warnings.size(), 2u);
  EXPECT_NE(m.warnings[0].find("top-level entry 'j3_controler' is neither a controller (no 'type' key) nor "
                               "gazebo_ros_control"),
            std::string::npos)
      << m.warnings[0];
  EXPECT_NE(m.warnings[1].find("'some_setting'"), std::string::npos) << m.warnings[1];
  EXPECT_EQ(m.controllers.size(), 3u);
}

TEST(Validation, PidGainsForAJointNotInTheUrdf) {
  std::string y = kYaml;
  y.replace(y.find("    j2:\n"), 8, "    j7:\n");
  const auto e = load_error(slurp(lt::source("config/turret_bot.urdf")), y);
  EXPECT_NE(e.find("gazebo_ros_control/pid_gains/j7: joint 'j7' is not in the URDF"), std::string::npos) << e;
}

TEST(Validation, PidGainsWithoutPOrWithUnknownKey) {
  std::string y = kYaml;
  y.replace(y.find("      p: 150\n"), 13, "      kp: 150\n");
  const auto e = load_error(slurp(lt::source("config/turret_bot.urdf")), y);
  EXPECT_NE(e.find("gazebo_ros_control/pid_gains/j1/kp: unknown key"), std::string::npos) << e;
  EXPECT_NE(e.find("gazebo_ros_control/pid_gains/j1: no 'p' gain (required)"), std::string::npos) << e;
}

TEST(Validation, IWithoutIClampIsWarned) {
  std::string y = kYaml;
  y.replace(y.find("      i: 0\n"), 11, "      i: 5\n");
  const std::string dir = lt::temp_dir("validation");
  const RobotModel m = load_robot_model(lt::source("config/turret_bot.urdf"), write(dir, "c.yaml", y));
  ASSERT_EQ(m.warnings.size(), 1u);
  EXPECT_NE(m.warnings[0].find("pid_gains/j1: i is 5 but i_clamp is 0"), std::string::npos) << m.warnings[0];
}

TEST(Validation, EveryProblemIsReportedNotJustTheFirst) {
  std::string u = turret_urdf_with("<mechanicalReduction>1</mechanicalReduction>", "<mechanicalReduction>0</mechanicalReduction>");
  const std::string from = "upper=\"3.14\" effort=\"1000\" velocity=\"50\"";
  u.replace(u.find(from), from.size(), "upper=\"3.14\" effort=\"1000\" velocity=\"0\"");
  const auto e = load_error(u, kYaml);
  EXPECT_NE(e.find("cannot be zero"), std::string::npos) << e;
  EXPECT_NE(e.find("velocity=\"0\""), std::string::npos) << e;
}

// The doctor command: one clear line and a non-zero exit, never a trace or a crash.
struct BadInput {
  const char* name;
  const char* urdf;  // file content, or nullptr for a missing file
  const char* yaml;
  const char* expect;
};

class DoctorRejects : public ::testing::TestWithParam<BadInput> {};

TEST_P(DoctorRejects, WithOneClearLine) {
  const BadInput& b = GetParam();
  const std::string dir = lt::temp_dir("doctor");
  const std::string u = b.urdf ? write(dir, "r.urdf", b.urdf) : dir + "/missing.urdf";
  const std::string y = b.yaml ? write(dir, "r.yaml", b.yaml) : dir + "/missing.yaml";
  lt::ChildProcess p({lt::bin("doctor"), "--urdf", u, "--config", y});
  const int rc = p.wait(20);
  const std::string out = p.output();
  EXPECT_EQ(rc, 3) << out;
  EXPECT_NE(out.find(b.expect), std::string::npos) << out;
  EXPECT_EQ(std::count(out.begin(), out.end(), '\n'), 1) << out;
  EXPECT_EQ(out.rfind("doctor: error: ", 0), 0u) << out;
  EXPECT_EQ(out.find("terminate"), std::string::npos) << out;
}

const char* kGoodUrdf = R"(<robot name="r"><link name="a"/></robot>)";

INSTANTIATE_TEST_SUITE_P(
    Files, DoctorRejects,
    ::testing::Values(
        BadInput{"MissingUrdf", nullptr, "{}", "missing.urdf: URDF file not found"},
        BadInput{"MissingYaml", kGoodUrdf, nullptr, "missing.yaml: config file not found"},
        BadInput{"MalformedXml", "<robot name='r'><link name='a'></robot>", "{}", "r.urdf:1: malformed XML"},
        BadInput{"NotAUrdf", "<html/>", "{}", "no <robot> element"},
        BadInput{"UrdfdomRejects", "<robot name='r'><link name='a'/><joint name='j' type='revolute'><parent link='a'/><child link='b'/></joint></robot>", "{}", "r.urdf: invalid URDF"},
        BadInput{"MalformedYaml", kGoodUrdf, "a: [1,\n", "r.yaml:2:1: malformed YAML"},
        BadInput{"YamlNotAMap", kGoodUrdf, "- 1\n- 2\n", "r.yaml: expected a map of controllers"},
        BadInput{"EmptyYaml", kGoodUrdf, "", "r.yaml: the file is empty"}),
    [](const auto& info) { return std::string(info.param.name); });

// Numbers Bullet would turn into non-finite states (they passed doctor with exit 0, issue 18): a 1e308 or NaN mass,
// a 1e308 effort limit, an infinite origin. Each is one problem naming the file, the link or joint and the value.
TEST(Validation, NonFiniteOrAbsurdNumbersAreRefused) {
  struct Case {
    std::string from, to, expect;
  };
  for (const Case& c : std::vector<Case>{
           {"<mass value=\"16\"/>", "<mass value=\"1e308\"/>", "link 'base': <mass value> is 1e+308"},
           {"<mass value=\"16\"/>", "<mass value=\"nan\"/>", "link 'base': <mass value=\"nan\"> is not a finite number"},
           {"<mass value=\"9.8075\"/>", "<mass value=\"-inf\"/>", "robot.urdf:35: link 'slider': <mass value=\"-inf\"> is not a finite number"},
           {"upper=\"1\" effort=\"1000\"", "upper=\"1\" effort=\"1e308\"", "joint 'j1': <limit effort> is 1e+308"},
           {"<origin xyz=\"0 0.05 0.165\"", "<origin xyz=\"0 1e300 0.165\"", "is 1e+300"},
       }) {
    const auto e = load_error(turret_urdf_with(c.from, c.to), kYaml);
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.to << "\n" << e;
    EXPECT_NE(e.find("robot.urdf"), std::string::npos) << e;
  }
}

namespace {
std::string gripper_with(const std::string& from, const std::string& to) {
  return urdf_with("test/robots/gripper.urdf", from, to);
}
const std::string kGripperYaml = slurp(lt::source("test/robots/gripper.yaml"));
}  // namespace

TEST(Validation, MimicJointsAreReadAndTheirMistakesNamed) {
  const RobotModel m = load_robot_model(lt::source("test/robots/gripper.urdf"), lt::source("test/robots/gripper.yaml"));
  const Joint* right = m.joint("right_finger_joint");
  ASSERT_TRUE(right && right->mimic);
  EXPECT_EQ(right->mimic->joint, "left_finger_joint");
  EXPECT_EQ(right->mimic->multiplier, 1.0);
  EXPECT_TRUE(m.self_collide);

  auto e = load_error(gripper_with(R"(<mimic joint="left_finger_joint")", R"(<mimic joint="left_fnger_joint")"),
                      kGripperYaml);
  EXPECT_NE(e.find("joint 'right_finger_joint' <mimic joint=\"left_fnger_joint\">: there is no joint 'left_fnger_joint'"),
            std::string::npos)
      << e;
  e = load_error(gripper_with(R"(multiplier="1")", R"(multiplier="one")"), kGripperYaml);
  EXPECT_NE(e.find("multiplier"), std::string::npos) << e;
  e = load_error(gripper_with(R"(<mimic joint="left_finger_joint")", R"(<mimic joint="right_finger_joint")"),
                 kGripperYaml);
  EXPECT_NE(e.find("a joint cannot mimic itself"), std::string::npos) << e;
  e = load_error(gripper_with(R"(<mimic joint="left_finger_joint")", R"(<mimic joint="box_mount")"), kGripperYaml);
  EXPECT_NE(e.find("that joint is fixed; mimic a moving joint"), std::string::npos) << e;
}

TEST(Validation, AMimicJointWithATransmissionIsDrivenByItAsInGazebo) {
  const std::string second = R"(<transmission name="right_transmission">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="right_finger_joint"><hardwareInterface>hardware_interface/PositionJointInterface</hardwareInterface></joint>
    <actuator name="right_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
  <gazebo>)";
  const std::string dir = lt::temp_dir("mimic_transmission");
  const RobotModel m = load_robot_model(write(dir, "g.urdf", gripper_with("<gazebo>", second)),
                                       write(dir, "g.yaml", kGripperYaml));
  EXPECT_FALSE(m.joint("right_finger_joint")->mimic);
  std::string w;
  for (const auto& x : m.warnings) w += x + "\n";
  EXPECT_NE(w.find("joint 'right_finger_joint' mimics 'left_finger_joint' but transmission 'right_transmission' drives "
                   "it: it is driven by its transmission, as in Gazebo"),
            std::string::npos)
      << w;
}

// A joint nothing drives (no transmission) with ROS packages' <limit effort="0" velocity="0">: a passive joint
// (a wheel drop, a caster), accepted with one note; the same limits on an actuated joint are still refused.
TEST(Validation, ZeroLimitsOnAJointNothingDrivesMakeItPassive) {
  const std::string passive = R"(  <link name="caster"><inertial><mass value="0.1"/><inertia ixx="1e-4" ixy="0" ixz="0" iyy="1e-4" iyz="0" izz="1e-4"/></inertial></link>
  <joint name="caster_joint" type="continuous">
    <parent link="rotor"/><child link="caster"/><axis xyz="0 1 0"/>
    <limit effort="0" velocity="0"/>
  </joint>
</robot>)";
  const std::string text = turret_urdf_with("</robot>", passive);
  std::string path;
  EXPECT_EQ(load_error(text, kYaml, &path), "");
  const RobotModel m = load_robot_model(path, "");
  bool noted = false;
  for (const auto& n : m.notes)
    noted = noted || n.find("joint 'caster_joint' is passive (nothing drives it): it moves freely, and its <limit "
                            "effort=\"0\" velocity=\"0\"> applies to no actuator") != std::string::npos;
  EXPECT_TRUE(noted);
}

// The Gazebo tags a mobile base's files use: per link <mu1>, <mu2>, <fdir1> (with gz:expressed_in), per joint
// <springStiffness>, <springReference>, <implicitSpringDamper>; what they get wrong is named with the file and line.
TEST(Validation, GazeboFrictionDirectionsAndSpringsAreReadAndBadOnesNamed) {
  const std::string tags = R"(  <gazebo reference="rotor"><mu1>0.8</mu1><mu2>0</mu2><fdir1 gz:expressed_in="base">0 2 0</fdir1></gazebo>
  <gazebo reference="j2"><springStiffness>30</springStiffness><springReference>0.5</springReference><implicitSpringDamper>true</implicitSpringDamper></gazebo>
</robot>)";
  std::string path;
  ASSERT_EQ(load_error(turret_urdf_with("</robot>", tags), kYaml, &path), "");
  const RobotModel m = load_robot_model(path, "");
  const Link* rotor = m.link("rotor");
  ASSERT_TRUE(rotor->friction_direction);
  EXPECT_EQ(*rotor->friction, 0.8);
  EXPECT_EQ(rotor->friction_direction->mu2, 0.0);
  EXPECT_EQ(rotor->friction_direction->frame, "base");
  EXPECT_TRUE(rotor->friction_direction->fdir1.isApprox(Eigen::Vector3d::UnitY()));
  ASSERT_TRUE(m.joint("j2")->spring);
  EXPECT_EQ(m.joint("j2")->spring->stiffness, 30);
  EXPECT_EQ(m.joint("j2")->spring->reference, 0.5);
  for (const auto& w : m.warnings) EXPECT_EQ(w.find("springStiffness"), std::string::npos) << "read, not warned: " << w;

  std::string e = load_error(turret_urdf_with("</robot>", R"(<gazebo reference="rotor"><fdir1>0 0</fdir1></gazebo></robot>)"),
                             kYaml, &path);
  EXPECT_NE(e.find(path + ":"), std::string::npos) << e;
  EXPECT_NE(e.find("link 'rotor': <fdir1>0 0</fdir1> is not a direction; write three numbers"), std::string::npos) << e;
  e = load_error(turret_urdf_with("</robot>", R"(<gazebo reference="rotor"><fdir1 gz:expressed_in="chassis">1 0 0</fdir1></gazebo></robot>)"), kYaml);
  EXPECT_NE(e.find("link 'rotor': <fdir1 expressed_in=\"chassis\">: there is no link 'chassis'"), std::string::npos) << e;
  e = load_error(turret_urdf_with("</robot>", R"(<gazebo reference="j2"><springStiffness>stiff</springStiffness></gazebo></robot>)"), kYaml);
  EXPECT_NE(e.find("<gazebo reference=\"j2\"><springStiffness>stiff</springStiffness> is not a number >= 0"),
            std::string::npos)
      << e;
}
