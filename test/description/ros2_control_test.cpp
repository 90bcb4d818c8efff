// The <ros2_control> block of a ROS 2 URDF, one rule per test, on the project's
// own small robot: a 2-joint arm, a 2-finger gripper with a mimic finger, a
// wheel. Each reproduces a trait of the real ROS 2 robots (gz_ros2_control's
// demos, UR, Robotiq, ros2_control_demos) and checks exact values and messages.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

// base -> joint1 (revolute +-3, effort 100, velocity 2) -> joint2 (revolute +-2.5) -> tool (fixed);
// base -> finger_r (prismatic 0..0.04) and finger_l (mimics finger_r, x -1, offset 0.01); base -> wheel (continuous).
const char* kLinksAndJoints = R"(
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="l1"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="l2"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool"/>
  <link name="fr"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="fl"><inertial><mass value="0.1"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="wheel"><inertial><mass value="0.5"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="100" velocity="2"/></joint>
  <joint name="joint2" type="revolute"><parent link="l1"/><child link="l2"/><origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>
    <limit lower="-2.5" upper="2.5" effort="50" velocity="2"/></joint>
  <joint name="tool_joint" type="fixed"><parent link="l2"/><child link="tool"/></joint>
  <joint name="finger_r" type="prismatic"><parent link="base"/><child link="fr"/><axis xyz="0 1 0"/>
    <limit lower="0" upper="0.04" effort="20" velocity="0.1"/></joint>
  <joint name="finger_l" type="prismatic"><parent link="base"/><child link="fl"/><mimic joint="finger_r" multiplier="-1" offset="0.01"/>
    <axis xyz="0 1 0"/><limit lower="-0.04" upper="0.05" effort="20" velocity="0.1"/></joint>
  <joint name="wheel_joint" type="continuous"><parent link="base"/><child link="wheel"/><axis xyz="0 0 1"/></joint>
)";

std::string robot_with(const std::string& ros2) {
  return std::string("<?xml version=\"1.0\"?>\n<robot name=\"r2bot\">") + kLinksAndJoints + ros2 + "</robot>\n";
}

std::string write(const std::string& dir, const std::string& name, const std::string& text) {
  const std::string p = dir + "/" + name;
  std::ofstream(p) << text;
  return p;
}

struct Loaded {
  std::string path;
  std::string text;
  std::optional<RobotModel> model;
  std::string error;  // ModelError's text, "" if it loaded
};

Loaded load(const std::string& ros2, const LoadOptions& options = {}) {
  Loaded l;
  l.text = robot_with(ros2);
  l.path = write(lt::temp_dir("ros2_control"), "r2bot.urdf", l.text);
  try {
    l.model = load_robot_model(l.path, "", options);
  } catch (const ModelError& e) {
    l.error = e.what();
  }
  return l;
}

// The 1-based line of the first `needle` in `text`.
int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << needle << "' not in the URDF";
  return 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

std::string lines(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& l : v) s += l + "\n";
  return s;
}

const char* kGzPlugin = R"(
  <gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
    <parameters>/opt/r2bot/config/controllers.yaml</parameters>
  </plugin></gazebo>
)";

}  // namespace

TEST(Ros2Control, GazeboSimArmWithPositionMinMaxAndInitialValue) {
  const Loaded l = load(std::string(R"(
  <ros2_control name="GazeboSimSystem" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1">
      <command_interface name="position"><param name="min">-1</param><param name="max">1</param></command_interface>
      <state_interface name="position"><param name="initial_value">0.5</param></state_interface>
      <state_interface name="velocity"/>
    </joint>
    <joint name="joint2">
      <command_interface name="position"><param name="min">-2</param><param name="max">4</param></command_interface>
      <state_interface name="position"/>
    </joint>
  </ros2_control>)") + kGzPlugin);
  ASSERT_TRUE(l.model) << l.error;
  const RobotModel& m = *l.model;
  ASSERT_EQ(m.ros2_control.size(), 1u);
  const HardwareBlock& b = m.ros2_control[0];
  EXPECT_EQ(b.name, "GazeboSimSystem");
  EXPECT_EQ(b.type, "system");
  EXPECT_EQ(b.plugin, "gz_ros2_control/GazeboSimSystem");
  EXPECT_EQ(b.kind, HardwareKind::Simulator);
  ASSERT_EQ(b.joints.size(), 2u);
  const Ros2Interface* cmd = b.joints[0].command_interface("position");
  ASSERT_TRUE(cmd);
  EXPECT_EQ(cmd->min, -1.0);
  EXPECT_EQ(cmd->max, 1.0);
  EXPECT_EQ(b.joints[0].state_interface("position")->initial_value, 0.5);
  EXPECT_EQ(b.joints[0].state_interfaces.size(), 2u);

  ASSERT_EQ(m.transmissions.size(), 2u);
  EXPECT_EQ(m.actuated_joints(), (std::vector<std::string>{"joint1", "joint2"}));
  const TransmissionSpec& t = m.transmissions[0];
  EXPECT_EQ(t.name, "GazeboSimSystem/joint1");
  EXPECT_EQ(t.type, "transmission_interface/SimpleTransmission");
  EXPECT_EQ(t.actuator, "joint1_actuator");
  EXPECT_EQ(t.interfaces, std::vector<Interface>{Interface::Position});
  EXPECT_EQ(t.map.reduction, 1.0);
  EXPECT_EQ(t.map.offset, 0.0);

  // min/max merged with the URDF <limit>: the stricter bound of each wins.
  EXPECT_EQ(m.joint("joint1")->lower, -1.0);
  EXPECT_EQ(m.joint("joint1")->upper, 1.0);
  EXPECT_EQ(m.joint("joint2")->lower, -2.0);
  EXPECT_EQ(m.joint("joint2")->upper, 2.5);
  const int j1 = line_of(l.text, "<joint name=\"joint1\">"), j2 = line_of(l.text, "<joint name=\"joint2\">");
  EXPECT_EQ(m.notes, (std::vector<std::string>{
                         fmt::format("{}:{}: ros2_control 'GazeboSimSystem': joint 'joint1': position min/max [-1, 1] is "
                                     "stricter than the URDF <limit> [-3, 3]; using [-1, 1]",
                                     l.path, j1),
                         fmt::format("{}:{}: ros2_control 'GazeboSimSystem': joint 'joint2': position min/max [-2, 4] is "
                                     "stricter than the URDF <limit> [-2.5, 2.5]; using [-2, 2.5]",
                                     l.path, j2)}))
      << lines(m.notes);
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
  EXPECT_EQ(m.initial_positions, (InitialPositions{{"joint1", 0.5}}));
  EXPECT_TRUE(m.initial_velocities.empty());

  EXPECT_TRUE(m.ros2_control_plugin.present);
  EXPECT_EQ(m.ros2_control_plugin.filename, "gz_ros2_control-system");
  EXPECT_EQ(m.ros2_control_plugin.name, "gz_ros2_control::GazeboSimROS2ControlPlugin");
  EXPECT_EQ(m.ros2_control_plugin.parameters, std::vector<std::string>{"/opt/r2bot/config/controllers.yaml"});
  EXPECT_FALSE(m.has_gazebo_ros_control_plugin);
}

TEST(Ros2Control, UrStylePositionAndVelocityCommandsWithInitialValues) {
  const Loaded l = load(R"(
  <ros2_control name="ur" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1">
      <command_interface name="position"/><command_interface name="velocity"/>
      <state_interface name="position"><param name="initial_value">-1.57</param></state_interface>
      <state_interface name="velocity"><param name="initial_value">0.0</param></state_interface>
      <state_interface name="effort"><param name="initial_value">0.0</param></state_interface>
    </joint>
    <joint name="joint2">
      <command_interface name="position"/><command_interface name="velocity"/>
      <state_interface name="position"><param name="initial_value">0.0</param></state_interface>
      <state_interface name="velocity"><param name="initial_value">0.25</param></state_interface>
    </joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const RobotModel& m = *l.model;
  ASSERT_EQ(m.transmissions.size(), 2u);
  for (const auto& t : m.transmissions)
    EXPECT_EQ(t.interfaces, (std::vector<Interface>{Interface::Position, Interface::Velocity})) << t.joint;
  EXPECT_EQ(m.initial_positions, (InitialPositions{{"joint1", -1.57}, {"joint2", 0.0}}));
  EXPECT_EQ(m.initial_velocities, (std::map<std::string, double>{{"joint1", 0.0}, {"joint2", 0.25}}));
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
  EXPECT_TRUE(m.notes.empty()) << lines(m.notes);  // no min/max: the URDF limits stand
  EXPECT_EQ(m.joint("joint1")->lower, -3.0);
  // Two command interfaces are normal in ROS 2: no "takes the first" warning as for ROS 1 transmissions.
}

TEST(Ros2Control, InitialValueOnTheCommandInterfaceIsTheStartWhenTheStateHasNone) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1">
      <command_interface name="position"><param name="initial_value">0.3</param></command_interface>
      <state_interface name="position"/>
    </joint>
    <joint name="joint2">
      <command_interface name="position"><param name="initial_value">0.3</param></command_interface>
      <state_interface name="position"><param name="initial_value">0.7</param></state_interface>
    </joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  EXPECT_EQ(l.model->initial_positions, (InitialPositions{{"joint1", 0.3}, {"joint2", 0.7}}));
  EXPECT_EQ(l.model->warnings,
            std::vector<std::string>{fmt::format("{}:{}: ros2_control 'arm': joint 'joint2': position initial_value 0.7 "
                                                 "on the state interface and 0.3 on the command interface; the joint "
                                                 "starts at the state's, 0.7",
                                                 l.path, line_of(l.text, "<joint name=\"joint2\">"))});
}

TEST(Ros2Control, GripperMimicJointListedWithoutCommandInterfaces) {
  const Loaded l = load(R"(
  <ros2_control name="GazeboSystem" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="finger_r">
      <command_interface name="position"/>
      <state_interface name="position"><param name="initial_value">0.015</param></state_interface>
      <state_interface name="velocity"/><state_interface name="effort"/>
    </joint>
    <joint name="finger_l">
      <state_interface name="position"/><state_interface name="velocity"/><state_interface name="effort"/>
    </joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const RobotModel& m = *l.model;
  EXPECT_EQ(m.actuated_joints(), std::vector<std::string>{"finger_r"});
  ASSERT_EQ(m.ros2_control[0].joints.size(), 2u);
  EXPECT_FALSE(m.ros2_control[0].joints[0].mimic);
  EXPECT_TRUE(m.ros2_control[0].joints[1].mimic);
  // The mimic stays a gear in the simulation, as today's URDF mimic joints are.
  ASSERT_TRUE(m.joint("finger_l")->mimic);
  EXPECT_EQ(m.joint("finger_l")->mimic->joint, "finger_r");
  EXPECT_EQ(m.joint("finger_l")->mimic->multiplier, -1.0);
  EXPECT_EQ(m.joint("finger_l")->mimic->offset, 0.01);
  EXPECT_EQ(m.initial_positions, (InitialPositions{{"finger_r", 0.015}}));
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
  EXPECT_TRUE(m.notes.empty()) << lines(m.notes);
}

TEST(Ros2Control, MimicJointWithACommandInterfaceIsRefused) {
  const Loaded l = load(R"(
  <ros2_control name="grip" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="finger_r"><command_interface name="position"/></joint>
    <joint name="finger_l"><command_interface name="position"/><command_interface name="velocity"/></joint>
  </ros2_control>)");
  EXPECT_EQ(l.error, fmt::format("{}:{}: ros2_control 'grip': joint 'finger_l': mimics 'finger_r' (URDF <mimic>) and has "
                                 "command interface position, velocity; a mimic joint takes no commands: remove its "
                                 "<command_interface>s, or add mimic=\"false\" to drive it on its own",
                                 l.path, line_of(l.text, "<joint name=\"finger_l\">")));
}

TEST(Ros2Control, MimickedJointMustBeInTheSameBlock) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="finger_r"><command_interface name="position"/></joint>
  </ros2_control>
  <ros2_control name="gripper" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="finger_l"><state_interface name="position"/></joint>
  </ros2_control>)");
  EXPECT_EQ(l.error, fmt::format("{}:{}: ros2_control 'gripper': joint 'finger_l': mimics 'finger_r', which is not in "
                                 "this <ros2_control> block; list 'finger_r' in it (ros2_control requires the mimicked "
                                 "joint in the same block)",
                                 l.path, line_of(l.text, "<joint name=\"finger_l\">")));
}

TEST(Ros2Control, MimicFalseDrivesTheJointOnItsOwn) {
  const Loaded l = load(R"(
  <ros2_control name="grip" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="finger_l" mimic="false"><command_interface name="effort"/><state_interface name="position"/></joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  EXPECT_EQ(l.model->actuated_joints(), std::vector<std::string>{"finger_l"});
  EXPECT_EQ(l.model->transmissions[0].interfaces, std::vector<Interface>{Interface::Effort});
  EXPECT_FALSE(l.model->joint("finger_l")->mimic);
  EXPECT_FALSE(l.model->ros2_control[0].joints[0].mimic);
  EXPECT_EQ(l.model->notes, std::vector<std::string>{fmt::format(
                                "{}:{}: ros2_control 'grip': joint 'finger_l': mimic=\"false\": driven on its own; the "
                                "URDF <mimic joint=\"finger_r\"> is not simulated",
                                l.path, line_of(l.text, "<joint name=\"finger_l\" mimic"))});
}

TEST(Ros2Control, MimicTrueWithoutAUrdfMimicIsRefused) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint2" mimic="true"><state_interface name="position"/></joint>
  </ros2_control>)");
  EXPECT_EQ(l.error, fmt::format("{}:{}: ros2_control 'arm': joint 'joint2': mimic=\"true\" but the URDF joint has no "
                                 "<mimic>; add <mimic joint=...> to the URDF joint or remove the attribute",
                                 l.path, line_of(l.text, "<joint name=\"joint2\" mimic")));
}

TEST(Ros2Control, ImuSensorIsReadAndPlacedOnItsFrameIdLink) {
  const Loaded l = load(R"(
  <ros2_control name="GazeboSimSystem" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="velocity"/><state_interface name="position"/></joint>
    <sensor name="base_imu">
      <state_interface name="orientation.x"/><state_interface name="orientation.y"/>
      <state_interface name="orientation.z"/><state_interface name="orientation.w"/>
      <state_interface name="angular_velocity.x"/><state_interface name="angular_velocity.y"/>
      <state_interface name="angular_velocity.z"/><state_interface name="linear_acceleration.x"/>
      <state_interface name="linear_acceleration.y"/><state_interface name="linear_acceleration.z"/>
      <param name="frame_id">tool</param>
    </sensor>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const HardwareBlock& b = l.model->ros2_control[0];
  ASSERT_EQ(b.sensors.size(), 1u);
  EXPECT_EQ(b.sensors[0].name, "base_imu");
  ASSERT_EQ(b.sensors[0].state_interfaces.size(), 10u);
  EXPECT_EQ(b.sensors[0].state_interfaces[3].name, "orientation.w");
  EXPECT_EQ(b.sensors[0].params, (Ros2Params{{"frame_id", "tool"}}));
  EXPECT_TRUE(l.model->notes.empty()) << lines(l.model->notes);
  ASSERT_EQ(l.model->sensors.size(), 1u);  // no <gazebo><sensor name="base_imu">: frame_id places it
  const SensorSpec& s = l.model->sensors[0];
  EXPECT_EQ(s.kind, SensorKind::Imu);
  EXPECT_EQ(s.link, "tool");
  EXPECT_EQ(s.hardware_block, "GazeboSimSystem");
  EXPECT_TRUE(s.simulated()) << s.not_simulated;
}

TEST(Ros2Control, GpioIsReadKeptAndNotedAsEchoingItsCommands) {
  const Loaded l = load(R"(
  <ros2_control name="hand" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="finger_r"><command_interface name="position"/><state_interface name="position"/></joint>
    <gpio name="reactivate">
      <command_interface name="reactivate_cmd"/><command_interface name="reactivate_response"/>
      <state_interface name="vacuum" data_type="bool"><param name="initial_value">false</param></state_interface>
    </gpio>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const HardwareBlock& b = l.model->ros2_control[0];
  ASSERT_EQ(b.gpios.size(), 1u);
  EXPECT_EQ(b.gpios[0].command_interfaces.size(), 2u);
  EXPECT_EQ(b.gpios[0].command_interfaces[1].name, "reactivate_response");
  EXPECT_EQ(b.gpios[0].state_interfaces[0].data_type, "bool");
  EXPECT_EQ(b.gpios[0].state_interfaces[0].params, (Ros2Params{{"initial_value", "false"}}));
  EXPECT_FALSE(b.gpios[0].state_interfaces[0].initial_value);  // a bool, not a number: kept as written
  EXPECT_EQ(l.model->notes, std::vector<std::string>{fmt::format(
                                "{}:{}: ros2_control 'hand': gpio 'reactivate' (2 command and 1 state interfaces): a "
                                "command interface echoes to the state interface of its name, as gz_ros2_control and "
                                "mock hardware do",
                                l.path, line_of(l.text, "<gpio name=\"reactivate\">"))});
  const GpioInterfaces g = gpio_interfaces(l.model->ros2_control);
  EXPECT_EQ(g.states, std::vector<std::string>{"reactivate/vacuum"});
  EXPECT_EQ(g.initial, std::vector<double>{0.0});  // "false"
  EXPECT_EQ(g.commands, (std::vector<std::string>{"reactivate/reactivate_cmd", "reactivate/reactivate_response"}));
}

TEST(Ros2Control, VendorDriverPluginIsRefusedNamingTheSimulationArguments) {
  const Loaded l = load(R"(
  <ros2_control name="ur" type="system">
    <hardware><plugin>ur_robot_driver/URPositionHardwareInterface</plugin>
      <param name="robot_ip">192.168.56.101</param></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>)");
  EXPECT_EQ(l.error,
            fmt::format("{}:{}: ros2_control 'ur': hardware plugin 'ur_robot_driver/URPositionHardwareInterface' is "
                        "neither a simulator nor mock hardware (a robot's driver or a package's own hardware) and cannot "
                        "be simulated; expand the xacro with the argument that selects simulated or mock hardware "
                        "(usually use_fake_hardware:=true, sim_gazebo:=true, use_gazebo:=true or sim_ignition:=true) so "
                        "that the block names gz_ros2_control/GazeboSimSystem or mock_components/GenericSystem, or "
                        "simulate it as it is with --simulate-hardware ur (a launch file's simulate_hardware: [ur])",
                        l.path, line_of(l.text, "<ros2_control name=\"ur\"")));
  // --simulate-hardware ur: the driver's block simulated, a note says so; a name that is no block is refused.
  LoadOptions o;
  o.simulate_hardware = {"ur"};
  const Loaded sim = load(R"(
  <ros2_control name="ur" type="system">
    <hardware><plugin>ur_robot_driver/URPositionHardwareInterface</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>)", o);
  ASSERT_TRUE(sim.model) << sim.error;
  EXPECT_EQ(sim.model->ros2_control[0].kind, HardwareKind::Simulator);
  EXPECT_NE(lines(sim.model->notes).find("hardware plugin 'ur_robot_driver/URPositionHardwareInterface' simulated in "
                                        "Bullet, as --simulate-hardware ur asks"),
            std::string::npos)
      << lines(sim.model->notes);
  o.simulate_hardware = {"arm"};
  const Loaded wrong = load(R"(
  <ros2_control name="ur" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>)", o);
  EXPECT_NE(wrong.error.find("--simulate-hardware arm: there is no <ros2_control name=\"arm\"> (the blocks: ur)"),
            std::string::npos)
      << wrong.error;
}

// Simulators are recognised by what their plugin is, vendors' forks too, and the note names the rule.
TEST(Ros2Control, AVendorsForkOfTheGzPluginIsASimulatorAndTheNoteSaysWhy) {
  for (const char* plugin : {"franka_ign_ros2_control/IgnitionSystem", "acme_gz_ros2_control/GazeboSimSystem",
                             "acme_robots/AcmeGzSystem", "gz_ros2_control::GazeboSimSystem"})
    EXPECT_EQ(hardware_kind(plugin), HardwareKind::Simulator) << plugin;
  EXPECT_EQ(hardware_kind("acme_mock/GenericSystem"), HardwareKind::Mock);
  const Loaded l = load(R"(
  <ros2_control name="fr3" type="system">
    <hardware><plugin>franka_ign_ros2_control/IgnitionSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="effort"/><state_interface name="position"/></joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  EXPECT_NE(lines(l.model->notes).find("hardware plugin 'franka_ign_ros2_control/IgnitionSystem' is a Gazebo/gz "
                                      "simulator system (class IgnitionSystem): played as a simulator here"),
            std::string::npos)
      << lines(l.model->notes);
}

TEST(Ros2Control, EveryKnownSimulatorAndMockPluginIsAccepted) {
  EXPECT_EQ(hardware_kind("gz_ros2_control/GazeboSimSystem"), HardwareKind::Simulator);
  EXPECT_EQ(hardware_kind("ign_ros2_control/IgnitionSystem"), HardwareKind::Simulator);
  EXPECT_EQ(hardware_kind("gazebo_ros2_control/GazeboSystem"), HardwareKind::Simulator);
  EXPECT_EQ(hardware_kind("mock_components/GenericSystem"), HardwareKind::Mock);
  EXPECT_EQ(hardware_kind("fake_components/GenericSystem"), HardwareKind::Mock);
  EXPECT_EQ(hardware_kind("ros2_control_demo_example_1/RRBotSystemPositionOnlyHardware"), HardwareKind::Mock);
  EXPECT_EQ(hardware_kind("robotiq_driver/RobotiqGripperHardwareInterface"), std::nullopt);
  EXPECT_EQ(hardware_kind("topic_based_ros2_control/TopicBasedSystem"), std::nullopt);
}

TEST(Ros2Control, MockComponentsWithHardwareParams) {
  const Loaded l = load(R"(
  <ros2_control name="ur" type="system">
    <hardware>
      <plugin>mock_components/GenericSystem</plugin>
      <param name="calculate_dynamics">true</param>
      <param name="mock_sensor_commands">False</param>
    </hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const HardwareBlock& b = l.model->ros2_control[0];
  EXPECT_EQ(b.kind, HardwareKind::Mock);
  EXPECT_STREQ(to_string(b.kind), "mock");
  EXPECT_EQ(b.params, (Ros2Params{{"calculate_dynamics", "true"}, {"mock_sensor_commands", "False"}}));
  EXPECT_EQ(l.model->actuated_joints(), std::vector<std::string>{"joint1"});
}

TEST(Ros2Control, Ros2TransmissionAppliesItsReductionAndOffsetToTheActuator) {
  const Loaded l = load(R"(
  <ros2_control name="RRBot" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
    <joint name="joint2"><command_interface name="position"/><state_interface name="position"/></joint>
    <transmission name="transmission1">
      <plugin>transmission_interface/SimpleTransmission</plugin>
      <actuator name="actuator1" role="actuator1"/>
      <joint name="joint1" role="joint1"><mechanical_reduction>2.0</mechanical_reduction><offset>0.1</offset></joint>
    </transmission>
    <transmission name="diff">
      <plugin>transmission_interface/DifferentialTransmission</plugin>
      <actuator name="a1" role="actuator1"/><actuator name="a2" role="actuator2"/>
      <joint name="joint1" role="joint1"/><joint name="joint2" role="joint2"/>
    </transmission>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const RobotModel& m = *l.model;
  ASSERT_EQ(m.transmissions.size(), 2u);
  EXPECT_EQ(m.transmissions[0].name, "transmission1");
  EXPECT_EQ(m.transmissions[0].actuator, "actuator1");
  EXPECT_EQ(m.transmissions[0].map.reduction, 2.0);
  EXPECT_EQ(m.transmissions[0].map.offset, 0.1);
  EXPECT_EQ(m.transmissions[1].name, "RRBot/joint2");
  EXPECT_EQ(m.transmissions[1].map.reduction, 1.0);
  ASSERT_EQ(m.ros2_control[0].transmissions.size(), 1u);
  EXPECT_EQ(m.warnings, std::vector<std::string>{fmt::format(
                            "{}:{}: ros2_control 'RRBot': transmission 'diff': skipped: plugin "
                            "'transmission_interface/DifferentialTransmission' is not supported (only "
                            "transmission_interface/SimpleTransmission is)",
                            l.path, line_of(l.text, "<transmission name=\"diff\">"))});
}

TEST(Ros2Control, ZeroReductionIsRefused) {
  const Loaded l = load(R"(
  <ros2_control name="RRBot" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/></joint>
    <transmission name="t1"><plugin>transmission_interface/SimpleTransmission</plugin><actuator name="a1"/>
      <joint name="joint1"><mechanical_reduction>0</mechanical_reduction></joint></transmission>
  </ros2_control>)");
  EXPECT_EQ(l.error, fmt::format("{}:{}: ros2_control 'RRBot': transmission 't1': <mechanical_reduction> is 0; a "
                                 "reduction ratio cannot be zero (use 1 for a direct drive, a negative value to flip the "
                                 "direction)",
                                 l.path, line_of(l.text, "<transmission name=\"t1\">")));
}

TEST(Ros2Control, BothTransmissionTagsAndABlockUseTheBlockAndSaySoOnce) {
  const Loaded l = load(R"(
  <transmission name="trans1"><type>transmission_interface/SimpleTransmission</type>
    <joint name="joint1"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m1"><mechanicalReduction>50</mechanicalReduction></actuator></transmission>
  <transmission name="trans2"><type>transmission_interface/SimpleTransmission</type>
    <joint name="joint2"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="m2"><mechanicalReduction>50</mechanicalReduction></actuator></transmission>
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="velocity"/><state_interface name="position"/></joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const RobotModel& m = *l.model;
  ASSERT_EQ(m.transmissions.size(), 1u);
  EXPECT_EQ(m.transmissions[0].interfaces, std::vector<Interface>{Interface::Velocity});
  EXPECT_EQ(m.transmissions[0].map.reduction, 1.0);
  EXPECT_EQ(m.notes, std::vector<std::string>{fmt::format("{}: has both <transmission> tags (2) and <ros2_control> "
                                                          "blocks; the <ros2_control> blocks are used, as ROS 2 does, "
                                                          "and the <transmission> tags are ignored",
                                                          l.path)});
  EXPECT_TRUE(m.warnings.empty()) << lines(m.warnings);
}

TEST(Ros2Control, JointsMustExistMoveAndBeListedOnce) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint_3"><command_interface name="position"/></joint>
    <joint name="tool_joint"><command_interface name="position"/></joint>
    <joint name="joint1"><command_interface name="position"/></joint>
  </ros2_control>
  <ros2_control name="again" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="effort"/></joint>
  </ros2_control>)");
  EXPECT_EQ(l.error,
            fmt::format("{0}:{1}: ros2_control 'arm': joint 'joint_3': not in the URDF (moving joints: joint1, joint2, "
                        "finger_r, finger_l, wheel_joint)\n"
                        "{0}:{2}: ros2_control 'arm': joint 'tool_joint': the joint is fixed; fixed joints cannot be in "
                        "ros2_control (remove it from the block or make it move)\n"
                        "{0}:{3}: ros2_control 'again': joint 'joint1': is already in ros2_control 'arm' (line {4}); "
                        "list each joint in one block",
                        l.path, line_of(l.text, "<joint name=\"joint_3\">"), line_of(l.text, "<joint name=\"tool_joint\">"),
                        line_of(l.text, "<joint name=\"joint1\"><command_interface name=\"effort\""),
                        line_of(l.text, "<joint name=\"joint1\">")));
}

TEST(Ros2Control, NoPluginIsRefused) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><param name="x">1</param></hardware>
    <joint name="joint1"><command_interface name="position"/></joint>
  </ros2_control>)");
  EXPECT_EQ(l.error, fmt::format("{}:{}: ros2_control 'arm': no <hardware><plugin>; name simulated or mock hardware, e.g. "
                                 "<plugin>gz_ros2_control/GazeboSimSystem</plugin> or "
                                 "<plugin>mock_components/GenericSystem</plugin>",
                                 l.path, line_of(l.text, "<ros2_control name=\"arm\"")));
}

TEST(Ros2Control, StateOnlyJointIsReportedNotActuated) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/></joint>
    <joint name="joint2"><state_interface name="position"/><state_interface name="velocity"/></joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  EXPECT_EQ(l.model->actuated_joints(), std::vector<std::string>{"joint1"});
  EXPECT_EQ(l.model->ros2_control[0].joints.size(), 2u);
  EXPECT_EQ(l.model->notes, std::vector<std::string>{fmt::format(
                                "{}:{}: ros2_control 'arm': joint 'joint2': state interfaces only: it is not actuated "
                                "(its state is reported)",
                                l.path, line_of(l.text, "<joint name=\"joint2\">"))});
}

TEST(Ros2Control, ContinuousWheelVelocityAndEffortLimitsFromMinMax) {
  const Loaded l = load(R"(
  <ros2_control name="base" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="wheel_joint">
      <command_interface name="velocity"><param name="min">-1</param><param name="max">1.5</param></command_interface>
      <command_interface name="effort"><param name="min">-7</param><param name="max">7</param></command_interface>
      <command_interface name="position"><param name="min">-10</param><param name="max">10</param></command_interface>
      <state_interface name="position"/><state_interface name="velocity"/>
    </joint>
    <joint name="joint1">
      <command_interface name="acceleration"/><state_interface name="position"/>
    </joint>
  </ros2_control>)");
  ASSERT_TRUE(l.model) << l.error;
  const RobotModel& m = *l.model;
  const Joint* w = m.joint("wheel_joint");
  EXPECT_EQ(w->velocity_limit, 1.0);  // the smaller magnitude of min and max
  EXPECT_EQ(w->effort_limit, 7.0);
  EXPECT_FALSE(w->has_position_limits);
  EXPECT_EQ(m.transmissions[0].interfaces,
            (std::vector<Interface>{Interface::Velocity, Interface::Effort, Interface::Position}));
  EXPECT_EQ(m.ros2_control[0].joints[0].command_interface("position")->max, 10.0);
  const std::string wheel = fmt::format("{}:{}: ros2_control 'base': joint 'wheel_joint'", l.path,
                                        line_of(l.text, "<joint name=\"wheel_joint\">"));
  const std::string j1 =
      fmt::format("{}:{}: ros2_control 'base': joint 'joint1'", l.path, line_of(l.text, "<joint name=\"joint1\">"));
  EXPECT_EQ(m.notes, (std::vector<std::string>{
                         wheel + ": velocity min/max [-1, 1.5] is stricter than the URDF (no velocity limit); using 1",
                         wheel + ": effort min/max [-7, 7] is stricter than the URDF (no effort limit); using 7",
                         wheel + ": position command limits [-10, 10] recorded for the commands (ros2_control clamps "
                                 "commands to them); the continuous joint itself turns without limit"}))
      << lines(m.notes);
  // acceleration is read, but no actuator takes it yet.
  EXPECT_EQ(m.warnings, std::vector<std::string>{j1 + ": command interface acceleration is read but not simulated "
                                                      "(position, velocity and effort are); the joint is not actuated"});
  EXPECT_EQ(m.actuated_joints(), std::vector<std::string>{"wheel_joint"});
}

TEST(Ros2Control, NonNumericInitialValueIsRefusedAndMinAboveMaxToo) {
  const Loaded l = load(R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1">
      <command_interface name="position"><param name="min">1</param><param name="max">-1</param></command_interface>
      <state_interface name="position"><param name="initial_value">up</param></state_interface>
    </joint>
  </ros2_control>)");
  const std::string where = fmt::format("{}:{}: ros2_control 'arm': joint 'joint1'", l.path,
                                        line_of(l.text, "<joint name=\"joint1\">"));
  EXPECT_EQ(l.error, where + ": command_interface 'position': min 1 is above max -1; swap them\n" + where +
                         ": state_interface 'position': <param name=\"initial_value\"> 'up' is not a number");
}

TEST(Ros2Control, ClassicGazeboPluginTagWithANamespace) {
  const Loaded l = load(R"(
  <ros2_control name="GazeboSystem" type="system">
    <hardware><plugin>gazebo_ros2_control/GazeboSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="effort"/><state_interface name="position"/></joint>
  </ros2_control>
  <gazebo><plugin filename="libgazebo_ros2_control.so" name="gazebo_ros2_control">
    <ros><namespace>/r2</namespace></ros>
    <parameters>a.yaml</parameters><parameters>b.yaml</parameters>
    <controller_manager_name>cm</controller_manager_name>
  </plugin></gazebo>)");
  ASSERT_TRUE(l.model) << l.error;
  const Ros2ControlPlugin& p = l.model->ros2_control_plugin;
  EXPECT_TRUE(p.present);
  EXPECT_EQ(p.filename, "libgazebo_ros2_control.so");
  EXPECT_EQ(p.parameters, (std::vector<std::string>{"a.yaml", "b.yaml"}));
  EXPECT_EQ(p.ns, "/r2");
  EXPECT_EQ(p.controller_manager_name, "cm");
  EXPECT_FALSE(l.model->has_gazebo_ros_control_plugin);
  EXPECT_TRUE(l.model->warnings.empty()) << lines(l.model->warnings);  // no "no gazebo_ros_control plugin" warning
}

namespace {
const char* kArmBlock = R"(
  <ros2_control name="arm" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><command_interface name="velocity"/></joint>
  </ros2_control>)";
}  // namespace

TEST(Ros2Control, EveryCommandInterfaceOfAJointIsTakenAtRunTime) {
  const Loaded l = load(kArmBlock);
  ASSERT_TRUE(l.model) << l.error;
  ASSERT_EQ(l.model->transmissions.size(), 1u);
  EXPECT_TRUE(l.model->transmissions[0].any_interface);
  EXPECT_EQ(l.model->transmissions[0].interfaces, (std::vector<Interface>{Interface::Position, Interface::Velocity}));
}

TEST(Ros2Control, HoldJointsDefaultsToTrueAndReadsFalse) {
  const Loaded held = load(std::string(kArmBlock) + R"(
  <gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin"/></gazebo>)");
  ASSERT_TRUE(held.model) << held.error;
  EXPECT_TRUE(held.model->ros2_control_plugin.hold_joints);
  EXPECT_FALSE(held.model->ros2_control_plugin.position_proportional_gain);

  const Loaded free = load(std::string(kArmBlock) + R"(
  <gazebo><plugin filename="gz_ros2_control-system" name="gz_ros2_control::GazeboSimROS2ControlPlugin">
    <hold_joints>false</hold_joints>
    <position_proportional_gain>0.5</position_proportional_gain>
  </plugin></gazebo>)");
  ASSERT_TRUE(free.model) << free.error;
  EXPECT_FALSE(free.model->ros2_control_plugin.hold_joints);
  EXPECT_EQ(free.model->ros2_control_plugin.position_proportional_gain, 0.5);
  const std::string note = fmt::format("{}:{}: <position_proportional_gain> 0.5 is ignored", free.path,
                                       line_of(free.text, "<position_proportional_gain>"));
  EXPECT_NE(lines(free.model->notes).find(note), std::string::npos) << lines(free.model->notes);
}

TEST(Ros2Control, HoldJointsThatIsNotABoolIsRefusedWithItsLine) {
  const Loaded l = load(std::string(kArmBlock) + R"(
  <gazebo><plugin filename="gz_ros2_control-system" name="p"><hold_joints>maybe</hold_joints></plugin></gazebo>)");
  EXPECT_EQ(l.error, fmt::format("{}:{}: <plugin filename=\"gz_ros2_control-system\">: <hold_joints> 'maybe' is not a "
                                 "bool; write true (joints nobody commands are held still, the default) or false",
                                 l.path, line_of(l.text, "<hold_joints>")));
}

// Without a config, the controllers come from the gz_ros2_control plugin's <parameters>, as gz_ros2_control reads
// them (relative: the working directory, else beside the URDF); one that is not a file is a warning, not an error.
TEST(Ros2Control, WithoutAConfigTheControllersComeFromThePluginParameters) {
  LoadOptions from_plugin;
  from_plugin.config_from_plugin = true;
  const RobotModel m = load_robot_model(lcm_control::testing::source("test/robots/switch_arm.urdf"), "", from_plugin);
  EXPECT_EQ(m.config_paths, std::vector<std::string>{lcm_control::testing::source("test/robots/switch_arm.yaml")});
  EXPECT_EQ(m.controllers.size(), 3u);
  EXPECT_TRUE(m.ros2_parameter_file);
  bool noted = false;
  for (const auto& n : m.notes) noted |= n.find("plugin's <parameters>") != std::string::npos;
  EXPECT_TRUE(noted);

  std::ifstream in(lcm_control::testing::source("test/robots/switch_arm.urdf"));
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string dir = lcm_control::testing::temp_dir("plugin_params");
  std::ofstream(dir + "/moved.urdf") << urdf;  // switch_arm.yaml is not beside it
  const RobotModel moved = load_robot_model(dir + "/moved.urdf", "", from_plugin);
  EXPECT_TRUE(load_robot_model(dir + "/moved.urdf", "").warnings.empty()) << "only when asked";
  EXPECT_TRUE(moved.controllers.empty());
  ASSERT_FALSE(moved.warnings.empty());
  EXPECT_NE(moved.warnings.back().find("<parameters> names switch_arm.yaml, which is not a file"), std::string::npos)
      << moved.warnings.back();
  std::filesystem::remove_all(dir);
}
