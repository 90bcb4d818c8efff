#include "controller_manager/ros_catalog.hpp"

#include <fmt/format.h>

#include <map>

#include "description/text.hpp"

namespace lcm_control::cm {

namespace {

const char* kRosControllers = "ros_controllers";
const char* kRos2Controllers = "ros2_controllers";

// Types by exact name, none of them built in here (registry_test checks it).
const std::map<std::string, std::string>& known_types() {
  static const std::map<std::string, std::string> types = [] {
    std::map<std::string, std::string> t;
    for (const char* name : {
            "pos_vel_controllers/JointTrajectoryController", "pos_vel_acc_controllers/JointTrajectoryController",
            "four_wheel_steering_controller/FourWheelSteeringController"})
      t[name] = kRosControllers;
    for (const char* name : {
            "gripper_controllers/GripperActionController", "range_sensor_broadcaster/RangeSensorBroadcaster",
            "pose_broadcaster/PoseBroadcaster", "gps_sensor_broadcaster/GPSSensorBroadcaster",
            "magnetometer_broadcaster/MagnetometerBroadcaster", "battery_state_broadcaster/BatteryStateBroadcaster",
            "state_interfaces_broadcaster/StateInterfacesBroadcaster",
            "chained_filter_controller/ChainedFilterController"})
      t.emplace(name, kRos2Controllers);
    return t;
  }();
  return types;
}

// Packages whose every type is known (robot vendors' and common third-party controllers).
const std::map<std::string, std::string>& known_packages() {
  static const std::map<std::string, std::string> packages = {
      {"franka_control", "franka_ros (Franka Emika)"},
      {"franka_example_controllers", "franka_ros (Franka Emika)"},
      {"franka_gazebo", "franka_ros (Franka Emika)"},
      {"ur_controllers", "Universal_Robots_ROS_Driver"},
      {"scaled_joint_trajectory_controller", "Universal_Robots_ROS_Driver"},
      {"pass_through_controllers", "Universal_Robots_ROS_Driver"},
      {"cartesian_trajectory_controller", "cartesian_controllers (FZI)"},
      {"cartesian_compliance_controller", "cartesian_controllers (FZI)"},
      {"cartesian_force_controller", "cartesian_controllers (FZI)"},
      {"cartesian_motion_controller", "cartesian_controllers (FZI)"},
      {"iiwa_control", "iiwa_stack (KUKA)"},
      {"kuka_rsi_hw_interface", "kuka_experimental (KUKA)"},
      {"robotiq_2f_gripper_control", "robotiq (Robotiq)"},
      {"twist_controller", "cartesian_controllers (FZI)"},
      {"rqt_joint_trajectory_controller", "ros_controllers"},
  };
  return packages;
}

}  // namespace

std::string ros_origin_of_type(const std::string& type) {
  const auto t = known_types().find(type);
  if (t != known_types().end()) return t->second;
  const auto slash = type.find('/');
  if (slash == std::string::npos) return "";
  const auto p = known_packages().find(type.substr(0, slash));
  return p == known_packages().end() ? "" : p->second;
}

std::vector<std::string> ros_catalog_types() {
  std::vector<std::string> names;
  for (const auto& [name, origin] : known_types()) names.push_back(name);
  return names;
}

std::string ros_alternative_to(const std::string& type) {
  static const std::map<std::string, std::string> alternatives = {
      {"pos_vel_controllers/JointTrajectoryController", "position_controllers/JointTrajectoryController"},
      {"pos_vel_acc_controllers/JointTrajectoryController", "position_controllers/JointTrajectoryController"},
      {"franka_example_controllers/JointPositionExampleController", "position_controllers/JointGroupPositionController"},
      {"franka_example_controllers/JointVelocityExampleController", "velocity_controllers/JointGroupVelocityController"},
      {"scaled_joint_trajectory_controller/ScaledJointTrajectoryController",
       "position_controllers/JointTrajectoryController (no speed scaling)"},
      {"position_controllers/ScaledJointTrajectoryController",
       "position_controllers/JointTrajectoryController (no speed scaling)"},
  };
  const auto it = alternatives.find(type);
  return it == alternatives.end() ? "" : it->second;
}

std::string unknown_type_message(const Registry& registry, const std::string& type) {
  const std::string origin = ros_origin_of_type(type);
  if (registry.misspelling(type))
    return fmt::format("controller type '{}' does not exist; did you mean '{}'? Valid types: {}", type, registry.closest(type),
                       join(registry.types()));
  if (!origin.empty()) {
    const std::string instead = ros_alternative_to(type);
    const bool vendor = origin != "ros_controllers" && origin != "ros2_controllers";
    return fmt::format("controller type '{}' ({}{}) is not {} here{} (`cmctl list-types` lists the {} "
                       "implemented types)",
                       type, vendor ? "a vendor's controller, " : "", origin, vendor ? "available" : "implemented",
                       instead.empty() ? "" : "; use " + instead, registry.types().size());
  }
  const std::string why = type.find('/') == std::string::npos
                              ? "no controller of this project is named so"
                              : fmt::format("package '{}' is not one whose controllers this project implements",
                                            type.substr(0, type.find('/')));
  return fmt::format("controller type '{}' is not available here: {} (`cmctl list-types` lists the {} implemented "
                     "types; a controller of your own is a plugin: user guide section 15)",
                     type, why, registry.types().size());
}

}  // namespace lcm_control::cm
