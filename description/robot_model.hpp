// The robot as both processes see it: URDF kinematics and dynamics, the
// transmissions that say which interface each joint takes, and the ros_control
// YAML (controllers and gazebo_ros_control pid_gains), loaded and validated once
// into plain structs.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "control/joint_limits.hpp"
#include "control/pid.hpp"
#include "control/transmission.hpp"
#include "description/initial_positions.hpp"
#include "description/ros2_control.hpp"
#include "description/sensors.hpp"

namespace lcm_control {

// A user-caused problem with the inputs. what() is one line per problem, each
// naming the file and the key, joint or link at fault and what to do.
class ModelError : public std::runtime_error {
 public:
  explicit ModelError(const std::vector<std::string>& problems);
  explicit ModelError(const std::string& problem) : ModelError(std::vector<std::string>{problem}) {}
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  std::vector<std::string> problems_;
};

enum class JointType { Revolute, Continuous, Prismatic, Fixed, Floating, Planar };
const char* to_string(JointType t);

enum class Interface { Position, Velocity, Effort };
const char* to_string(Interface i);  // "PositionJointInterface", ...
// Accepts "hardware_interface/PositionJointInterface" and "PositionJointInterface".
std::optional<Interface> parse_interface(const std::string& name);
// ROS 2's name of the quantity: "position", "velocity", "effort"; and back (nullopt for any other name).
const char* quantity_of(Interface i);
std::optional<Interface> interface_of_quantity(const std::string& name);

struct Geometry {
  enum class Type { Box, Cylinder, Sphere, Mesh } type = Type::Box;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // in the link frame
  Eigen::Vector3d size = Eigen::Vector3d::Zero();            // box
  double radius = 0, length = 0;                             // cylinder (along z), sphere
  std::string mesh_uri;                                      // as written in the URDF
  std::string mesh_path;                                     // resolved file, "" if not found
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
};

struct Inertial {
  double mass = 0;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // COM frame in the link frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();         // about the COM, in the COM frame
};

struct Link {
  std::string name;
  std::optional<Inertial> inertial;
  std::vector<Geometry> collisions;
  std::vector<Geometry> visuals;
  std::string parent_joint;  // "" for the root
  std::optional<double> friction;  // <gazebo reference="LINK"><mu1>: contact friction coefficient (default 1)
  // <gazebo reference="LINK"><fdir1> with <mu2>: friction mu1 along fdir1 and mu2 across it (a mecanum or omni
  // wheel's rollers, as Gazebo's ODE models them); without it the contact's friction is mu1 every way.
  struct FrictionDirection {
    Eigen::Vector3d fdir1 = Eigen::Vector3d::UnitX();  // unit, in `frame`
    std::string frame;                                  // the link it is expressed in (gz:expressed_in); "" this one
    double mu2 = 1;
  };
  std::optional<FrictionDirection> friction_direction;
  bool gravity_off = false;        // <gazebo reference="LINK"><turnGravityOff>true: the link feels no gravity
};

// <mimic joint= multiplier= offset=>: position = multiplier * the other joint's position + offset.
struct Mimic {
  std::string joint;
  double multiplier = 1, offset = 0;
};

struct Joint {
  std::string name;
  JointType type = JointType::Fixed;
  std::string parent_link, child_link;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();  // child frame in the parent link frame
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();
  bool has_position_limits = false;  // revolute and prismatic
  double lower = 0, upper = 0;
  double effort_limit = 0, velocity_limit = 0;  // 0 only for fixed joints (validated)
  double damping = 0, friction = 0;
  std::optional<SoftLimits> soft;  // <safety_controller>
  std::optional<Mimic> mimic;      // driven by another joint through a gear in the simulation; takes no transmission
  // <gazebo reference="JOINT"><springStiffness> (N*m/rad or N/m) and <springReference> (rad or m): a spring pulling
  // the joint towards the reference, -stiffness * (q - reference), as Gazebo simulates it.
  struct Spring {
    double stiffness = 0, reference = 0;
  };
  std::optional<Spring> spring;
  JointLimits limits() const {     // as joint_limits_interface reads them from the URDF
    JointLimits l;
    l.has_position = has_position_limits;
    l.lower = lower;
    l.upper = upper;
    l.max_velocity = velocity_limit;
    l.max_effort = effort_limit;
    return l;
  }
};

struct TransmissionSpec {
  std::string name;
  std::string type;  // "transmission_interface/SimpleTransmission"
  std::string joint;
  std::vector<Interface> interfaces;  // first one is the one the hardware takes by default
  // A <ros2_control> joint: the hardware takes commands in any of `interfaces`, switching at run time to the one the
  // running controller claims. False (a URDF <transmission>, ROS 1): only the first.
  bool any_interface = false;
  std::string actuator;
  std::string hardware_block;  // the <ros2_control> block declaring the joint, "" for a URDF <transmission>
  SimpleTransmission map;
  std::vector<Interface> skipped_interfaces;  // of the joint's other transmissions, skipped (the first drives it)
};

struct ControllerSpec {
  std::string name;
  std::string type;
  YAML::Node params;  // the whole YAML entry, `type` included
  std::string file;   // the config file(s) the entry came from, as messages name them
};

struct LoadOptions {
  // Folders searched for `package://NAME/...`: DIR/NAME/... and, if DIR's own
  // name is NAME, DIR/... . Defaults to $LCM_CONTROL_PACKAGE_PATH and
  // $ROS_PACKAGE_PATH (colon-separated) when empty.
  std::vector<std::string> package_path;
  // The robot's namespace from --namespace; "" takes the gazebo_ros_control plugin's <robotNamespace>.
  std::string ns;
  // Values for $(arg NAME) in the YAML (roslaunch's subst_value), from --arg NAME=VALUE.
  std::vector<std::pair<std::string, std::string>> args;
  // Arguments of a .xacro robot file (name:=value), from --xacro-arg or a launch file's `xacro_args:`.
  std::vector<std::pair<std::string, std::string>> xacro_args;
  // Factor on xacro's expansion budget (xacro --budget); 0 takes $LCM_CONTROL_XACRO_BUDGET, else 1.
  double xacro_budget = 0;
  // No config given: read the controllers from the gz_ros2_control plugin's <parameters>, as gz_ros2_control does
  // (the servers, doctor and launch; a program that needs only the URDF leaves it off).
  bool config_from_plugin = false;
  // <ros2_control> blocks (by name) to simulate whatever their plugin, from --simulate-hardware NAME (a launch file's
  // simulate_hardware:): a real robot's driver run in Bullet.
  std::vector<std::string> simulate_hardware;
};

struct RobotModel {
  std::string name;
  std::string urdf_path;
  // The controller YAML files (--config, repeatable), merged in order as rosparam loads them into one namespace: a
  // later file's key wins (maps merge key by key). config_path names them in messages ("a.yaml", "a.yaml + b.yaml").
  std::vector<std::string> config_paths;
  std::string config_path;
  // With several files: the file each leaf key path ("arm_controller/gains/j1/p") was set by.
  std::map<std::string, std::string> config_key_files;
  LoadOptions options;                          // as loaded (a reload reads the config again with them)
  std::string root_link;
  std::vector<Link> links;                     // URDF order
  std::vector<Joint> joints;                   // URDF order
  std::vector<TransmissionSpec> transmissions;  // URDF order = actuator order on the wire
  bool self_collide = false;  // <gazebo><self_collide>true: links collide with the robot's other links (not the adjacent ones)
  bool has_gazebo_ros_control_plugin = false;
  std::string gazebo_plugin_namespace;         // <robotNamespace>, if given
  // The robot's namespace ("" none, "rrbot", "lab/rrbot"): the channel prefix and where the YAML is read.
  std::string ns;
  std::string config_section;                  // the YAML key the controllers were read under, "" for the top level
  std::vector<ControllerSpec> controllers;     // YAML order
  std::map<std::string, PidGains> pid_gains;   // gazebo_ros_control/pid_gains/<joint>
  // ROS 2 (description/ros2_control.hpp, description/ros2_params.hpp): the <ros2_control> blocks in file order
  // (when there are any, `transmissions` are their joints' actuators), the gz_ros2_control plugin tag, the start
  // pose their initial_values give, and the controller_manager's update_rate from the parameter file.
  std::vector<HardwareBlock> ros2_control;
  Ros2ControlPlugin ros2_control_plugin;
  InitialPositions initial_positions;               // joint -> initial_value of its position interface
  std::map<std::string, double> initial_velocities;  // joint -> initial_value of its velocity interface
  std::optional<double> update_rate_hz;             // controller_manager: ros__parameters: update_rate
  // controller_manager: hardware_components_initial_state: unconfigured / inactive: components not started active.
  std::vector<std::string> components_start_unconfigured, components_start_inactive;
  bool ros2_parameter_file = false;                 // the config is a ROS 2 parameter file
  bool from_ros2() const { return !ros2_control.empty() || ros2_parameter_file; }  // ROS 2 users' files
  std::vector<SensorSpec> sensors;             // declared sensors, simulated or not (description/sensors.hpp)
  std::vector<std::string> notes;              // what was resolved and how, one INFO line each
  std::vector<std::string> warnings;           // non-fatal findings, one line each
  std::vector<std::string> hints;              // valid, but often not what was meant (doctor prints them)

  const Joint* joint(const std::string& name) const;
  const Link* link(const std::string& name) const;
  const TransmissionSpec* transmission_for_joint(const std::string& joint) const;
  const ControllerSpec* controller(const std::string& name) const;
  // The config file(s) that set a key path ("ctl/joints") or anything under it, as messages name them.
  std::string config_file_of(const std::string& key_path) const;
  // Joints that have a transmission, in transmission order (the hardware's joints).
  std::vector<std::string> actuated_joints() const;
};

// A namespace as written in ROS ("/rrbot/", "rrbot") as our channel prefix ("rrbot"); "" for "/" or "".
std::string normalize_namespace(const std::string& ns);
// The robot's namespace: the one given (--namespace), else the gazebo_ros_control plugin's <robotNamespace>.
std::string robot_namespace(const std::string& given, const std::string& plugin_namespace);

}  // namespace lcm_control
