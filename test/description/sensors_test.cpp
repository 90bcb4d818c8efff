// The sensors a description declares, one form per test, on the project's own 2-link arm: Gazebo's SDF <sensor>
// tags (imu, force_torque, contact, and kinds not simulated), ROS 1's sensor plugins, and the <sensor> of a
// <ros2_control> block matched to a Gazebo sensor by name, with exact values and messages.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

const char* kArm = R"(
  <link name="world"/>
  <link name="base"><inertial><mass value="5"/><inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="l1"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <link name="tool"><inertial><mass value="0.2"/><inertia ixx="0.001" iyy="0.001" izz="0.001" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="weld" type="fixed"><parent link="world"/><child link="base"/></joint>
  <joint name="joint1" type="revolute"><parent link="base"/><child link="l1"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="100" velocity="2"/></joint>
  <joint name="wrist_ft" type="fixed"><parent link="l1"/><child link="tool"/><origin xyz="0 0 0.4"/></joint>
)";

struct Loaded {
  std::string path, text;
  RobotModel model;
};

Loaded load(const std::string& extra) {
  Loaded l;
  l.text = std::string("<?xml version=\"1.0\"?>\n<robot name=\"sensor_arm\">") + kArm + extra + "</robot>\n";
  l.path = lt::temp_dir("sensors") + "/sensor_arm.urdf";
  std::ofstream(l.path) << l.text;
  l.model = load_robot_model(l.path, "");
  return l;
}

int line_of(const std::string& text, const std::string& needle) {
  const auto at = text.find(needle);
  EXPECT_NE(at, std::string::npos) << "test bug: '" << needle << "' not in the URDF";
  return 1 + int(std::count(text.begin(), text.begin() + long(at), '\n'));
}

bool has_warning(const RobotModel& m, const std::string& w) {
  return std::find(m.warnings.begin(), m.warnings.end(), w) != m.warnings.end();
}

std::string all(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& x : v) s += x + "\n";
  return s;
}

TEST(Sensors, SdfImuWithPerAxisNoiseAndPose) {
  const Loaded l = load(R"(
  <gazebo reference="tool">
    <sensor name="tool_imu" type="imu">
      <update_rate>200</update_rate>
      <pose>0.1 0 0 0 0 1.5707963267948966</pose>
      <imu>
        <angular_velocity><z><noise type="gaussian"><mean>0.001</mean><stddev>0.002</stddev></noise></z></angular_velocity>
        <linear_acceleration><x><noise type="gaussian"><stddev>0.017</stddev><bias_mean>0.1</bias_mean><bias_stddev>0.001</bias_stddev></noise></x></linear_acceleration>
      </imu>
      <plugin name="imu_plugin" filename="libgazebo_ros_imu_sensor.so"><frameName>tool_imu_link</frameName></plugin>
    </sensor>
  </gazebo>)");
  ASSERT_EQ(l.model.sensors.size(), 1u);
  const SensorSpec& s = l.model.sensors[0];
  EXPECT_EQ(s.kind, SensorKind::Imu);
  EXPECT_EQ(s.link, "tool");
  EXPECT_TRUE(s.simulated());
  EXPECT_EQ(s.update_rate_hz, 200);
  EXPECT_EQ(s.frame_id, "tool_imu_link");
  EXPECT_NEAR(s.pose.translation().x(), 0.1, 1e-12);
  EXPECT_NEAR(s.pose.linear()(1, 0), 1.0, 1e-12);  // yaw 90 deg: x goes to y
  EXPECT_EQ(s.angular_velocity[2].mean, 0.001);
  EXPECT_EQ(s.angular_velocity[2].stddev, 0.002);
  EXPECT_EQ(s.angular_velocity[0].stddev, 0);
  EXPECT_EQ(s.linear_acceleration[0].stddev, 0.017);
  EXPECT_EQ(s.linear_acceleration[0].bias_mean, 0.1);
  EXPECT_EQ(s.where, fmt::format("{}:{}", l.path, line_of(l.text, "<sensor name=\"tool_imu\"")));
  EXPECT_EQ(l.model.warnings, std::vector<std::string>{}) << all(l.model.warnings);
}

TEST(Sensors, OldSdfNoiseAndTheRos1ImuPlugins) {
  const Loaded l = load(R"(
  <gazebo reference="l1">
    <sensor name="old_imu" type="imu">
      <imu><noise><type>gaussian</type><rate><mean>0</mean><stddev>0.0003</stddev></rate><accel><mean>0</mean><stddev>0.02</stddev></accel></noise></imu>
    </sensor>
  </gazebo>
  <gazebo>
    <plugin name="classic_imu" filename="libgazebo_ros_imu.so">
      <bodyName>base</bodyName><topicName>imu</topicName><gaussianNoise>0.005</gaussianNoise><updateRateHZ>50</updateRateHZ>
    </plugin>
    <plugin name="hector_imu" filename="libhector_gazebo_ros_imu.so">
      <bodyName>tool</bodyName><frameId>tool_frame</frameId>
      <accelGaussianNoise>0.1 0.2 0.3</accelGaussianNoise><rateGaussianNoise>0.01 0.02 0.03</rateGaussianNoise>
      <accelDrift>0.1 0.1 0.1</accelDrift>
    </plugin>
  </gazebo>)");
  ASSERT_EQ(l.model.sensors.size(), 3u);
  const SensorSpec& old = l.model.sensors[0];
  EXPECT_EQ(old.angular_velocity[1].stddev, 0.0003);
  EXPECT_EQ(old.linear_acceleration[2].stddev, 0.02);
  const SensorSpec& classic = l.model.sensors[1];
  EXPECT_EQ(classic.kind, SensorKind::Imu);
  EXPECT_EQ(classic.link, "base");
  EXPECT_EQ(classic.update_rate_hz, 50);
  EXPECT_EQ(classic.linear_acceleration[0].stddev, 0.005);
  EXPECT_EQ(classic.angular_velocity[2].stddev, 0.005);
  const SensorSpec& hector = l.model.sensors[2];
  EXPECT_EQ(hector.link, "tool");
  EXPECT_EQ(hector.frame_id, "tool_frame");
  EXPECT_EQ(hector.linear_acceleration[2].stddev, 0.3);
  EXPECT_EQ(hector.angular_velocity[1].stddev, 0.02);
  EXPECT_TRUE(has_warning(l.model, fmt::format("{}:{}: sensor 'hector_imu': cannot read <accelDrift> (a random-walk "
                                               "drift, not simulated); it is simulated without them",
                                               l.path, line_of(l.text, "<plugin name=\"hector_imu\""))))
      << all(l.model.warnings);
  // Read here, so not among the Gazebo tags named as ignored.
  for (const auto& w : l.model.warnings) EXPECT_EQ(w.find("Gazebo tags not simulated"), std::string::npos) << w;
}

TEST(Sensors, ForceTorqueOnAJointSdfAndRos1Plugin) {
  const Loaded l = load(R"(
  <gazebo reference="wrist_ft">
    <provideFeedback>true</provideFeedback>
    <sensor name="wrist" type="force_torque">
      <force_torque><frame>sensor</frame><measure_direction>parent_to_child</measure_direction>
        <force><x><noise type="gaussian"><stddev>0.5</stddev></noise></x></force></force_torque>
    </sensor>
  </gazebo>
  <gazebo>
    <plugin name="ft_ros1" filename="libgazebo_ros_ft_sensor.so"><jointName>joint1</jointName><gaussianNoise>0.01</gaussianNoise></plugin>
  </gazebo>)");
  ASSERT_EQ(l.model.sensors.size(), 2u);
  const SensorSpec& sdf = l.model.sensors[0];
  EXPECT_EQ(sdf.kind, SensorKind::ForceTorque);
  EXPECT_EQ(sdf.joint, "wrist_ft");
  EXPECT_EQ(sdf.link, "tool");
  EXPECT_EQ(sdf.frame, WrenchFrame::Sensor);
  EXPECT_EQ(sdf.direction, MeasureDirection::ParentToChild);
  EXPECT_EQ(sdf.force[0].stddev, 0.5);
  const SensorSpec& ros1 = l.model.sensors[1];
  EXPECT_EQ(ros1.joint, "joint1");
  EXPECT_EQ(ros1.link, "l1");
  EXPECT_EQ(ros1.frame, WrenchFrame::Child);
  EXPECT_EQ(ros1.direction, MeasureDirection::ParentToChild);  // the joint's wrench on its child
  EXPECT_EQ(ros1.torque[2].stddev, 0.01);
  EXPECT_EQ(l.model.warnings, std::vector<std::string>{}) << all(l.model.warnings);
}

TEST(Sensors, WhatCannotBeSimulatedIsNamedWithWhy) {
  const Loaded l = load(R"(
  <gazebo reference="tool">
    <sensor name="cam" type="camera"><plugin name="c" filename="libgazebo_ros_camera.so"/></sensor>
    <sensor name="ft_on_link" type="force_torque"/>
  </gazebo>
  <gazebo reference="elbow">
    <sensor name="lost" type="imu"/>
  </gazebo>)");
  ASSERT_EQ(l.model.sensors.size(), 3u);
  for (const SensorSpec& s : l.model.sensors) EXPECT_FALSE(s.simulated()) << s.name;
  const auto where = [&](const char* n) { return fmt::format("{}:{}", l.path, line_of(l.text, n)); };
  EXPECT_TRUE(has_warning(l.model, where("<sensor name=\"cam\"") +
                                       ": sensor 'cam' (camera) is not simulated: the simulator has no camera "
                                       "sensors (it has imu, force_torque and contact)"))
      << all(l.model.warnings);
  EXPECT_TRUE(has_warning(l.model, where("<sensor name=\"ft_on_link\"") +
                                       ": sensor 'ft_on_link' (force_torque) is not simulated: a force_torque sensor "
                                       "measures a joint, and reference 'tool' is a link: write <gazebo "
                                       "reference=\"wrist_ft\"> (its parent joint)"))
      << all(l.model.warnings);
  EXPECT_TRUE(has_warning(l.model, where("<sensor name=\"lost\"") +
                                       ": sensor 'lost' (imu) is not simulated: reference 'elbow' is no link of the "
                                       "URDF"))
      << all(l.model.warnings);
}

TEST(Sensors, Ros2ControlSensorTakesTheGazeboSensorOfItsName) {
  const Loaded l = load(R"(
  <gazebo reference="wrist_ft">
    <sensor name="tcp_fts_sensor" type="force_torque"><force_torque><frame>child</frame></force_torque></sensor>
  </gazebo>
  <ros2_control name="GazeboSimSystem" type="system">
    <hardware><plugin>gz_ros2_control/GazeboSimSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
    <sensor name="tcp_fts_sensor">
      <state_interface name="force.x"/><state_interface name="force.y"/><state_interface name="force.z"/>
      <state_interface name="torque.x"/><state_interface name="torque.y"/><state_interface name="torque.z"/>
      <state_interface name="temperature"/>
      <param name="frame_id">tool0</param>
    </sensor>
  </ros2_control>)");
  ASSERT_EQ(l.model.sensors.size(), 1u);
  const SensorSpec& s = l.model.sensors[0];
  EXPECT_EQ(s.kind, SensorKind::ForceTorque);
  EXPECT_EQ(s.joint, "wrist_ft");
  EXPECT_EQ(s.hardware_block, "GazeboSimSystem");
  EXPECT_EQ(s.frame_id, "tool0");
  EXPECT_TRUE(has_warning(
      l.model, fmt::format("{}:{}: ros2_control 'GazeboSimSystem': sensor 'tcp_fts_sensor' (force_torque) has state "
                           "interface temperature that the simulator does not give (it gives force.x, force.y, "
                           "force.z, torque.x, torque.y, torque.z); they are not published",
                           l.path, line_of(l.text, "<sensor name=\"tcp_fts_sensor\">"))))
      << all(l.model.warnings);
}

TEST(Sensors, Ros2ControlSensorOnMockHardwareIsNotSimulated) {
  const Loaded l = load(R"(
  <ros2_control name="mock" type="system">
    <hardware><plugin>mock_components/GenericSystem</plugin></hardware>
    <joint name="joint1"><command_interface name="position"/><state_interface name="position"/></joint>
    <sensor name="fts"><state_interface name="force.x"/><param name="frame_id">tool</param></sensor>
  </ros2_control>)");
  ASSERT_EQ(l.model.sensors.size(), 1u);
  EXPECT_EQ(l.model.sensors[0].not_simulated, "mock hardware: its state interfaces hold their initial_value");
}

}  // namespace
