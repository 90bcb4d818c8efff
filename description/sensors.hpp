// The sensors a robot description declares, read into one list: Gazebo's <sensor> tags (classic and gz, in
// <gazebo reference="LINK or JOINT">), the ROS 1 sensor plugins (gazebo_ros_imu, hector's IMU,
// gazebo_ros_ft_sensor) and the <sensor> components of <ros2_control> blocks, which gz_ros2_control matches to a
// Gazebo sensor by name. sim_server simulates the IMU, force-torque and contact kinds from the Bullet state;
// every other sensor is listed with why it is not simulated.
#pragma once

#include <Eigen/Geometry>
#include <array>
#include <string>
#include <vector>

namespace tinyxml2 {
class XMLElement;
}

namespace lcm_control {

struct RobotModel;

enum class SensorKind { Imu, ForceTorque, Contact, Other };
const char* to_string(SensorKind k);  // "imu", "force_torque", "contact", "other"

// The state interfaces a kind provides, in the order the hardware sends them (ros2_control's names):
// imu: orientation.x..w, angular_velocity.x..z [rad/s], linear_acceleration.x..z [m/s^2];
// force_torque: force.x..z [N], torque.x..z [N*m]; contact: contact (1 touching, 0 not), normal_force [N].
const std::vector<std::string>& sensor_interfaces(SensorKind k);

// Gaussian noise on one measured component, as SDF's <noise type="gaussian"> gives it: every sample adds
// mean + N(0, stddev), and a bias drawn once at start from N(bias_mean, bias_stddev), with a random sign.
struct GaussianNoise {
  double mean = 0, stddev = 0, bias_mean = 0, bias_stddev = 0;
  bool any() const { return mean != 0 || stddev != 0 || bias_mean != 0 || bias_stddev != 0; }
};
using AxisNoise = std::array<GaussianNoise, 3>;  // x, y, z

// SDF's <force_torque><frame>: the frame the wrench is expressed in, all at the joint's origin.
enum class WrenchFrame { Child, Parent, Sensor };
// SDF's <force_torque><measure_direction>: child_to_parent measures the wrench the child applies on the parent,
// parent_to_child the one the parent applies on the child (its negative).
enum class MeasureDirection { ChildToParent, ParentToChild };

struct SensorSpec {
  std::string name;
  std::string type;   // as declared: "imu", "force_torque", "contact", "camera", "gpu_ray", ... or a plugin file
  SensorKind kind = SensorKind::Other;
  std::string link;   // the link it sits on (force-torque: the measured joint's child link)
  std::string joint;  // force-torque: the joint it measures
  // The sensor frame in the link frame (force-torque: in the joint's child frame, which is the child link's).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  WrenchFrame frame = WrenchFrame::Child;
  MeasureDirection direction = MeasureDirection::ChildToParent;
  AxisNoise angular_velocity, linear_acceleration, force, torque;
  double update_rate_hz = 0;  // as declared, 0 for none; simulated at every control step
  std::string frame_id;       // ROS frame name: ros2_control's frame_id param, a plugin's <frameName>; else the link
  std::string topic;          // the ROS topic it was declared with, for reference
  std::string hardware_block; // the <ros2_control> block listing it, "" for none
  std::string where;          // "file:line" of its tag
  std::string not_simulated;  // why it is not simulated, "" when it is

  bool simulated() const { return not_simulated.empty(); }
};

// The values the simulated ones among `sensors` send (hardware_state_t's num_sensor_values).
int sensor_value_count(const std::vector<SensorSpec>& sensors);

// Reads every sensor of the URDF into model.sensors (links, joints and <ros2_control> blocks must be read), with a
// warning naming each one not simulated (file:line, sensor, type, why). A sensor's tag that cannot be read (a
// reference to no link or joint, a noise value that is not a number) is a warning naming file, line and tag, and
// leaves it not simulated: a robot is never refused for its sensors, as Gazebo runs without them.
void read_sensors(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file);

}  // namespace lcm_control
