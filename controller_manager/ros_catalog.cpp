#include "controller_manager/ros_catalog.hpp"

#include <map>

namespace lcm_control::cm {

namespace {

const char* kRosControllers = "ros_controllers";
const char* kRos2Controllers = "ros2_controllers";

// Types by exact name.
const std::map<std::string, std::string>& known_types() {
  static const std::map<std::string, std::string> types = [] {
    std::map<std::string, std::string> t;
    for (const char* name : {
             "joint_state_controller/JointStateController",
             "position_controllers/JointPositionController", "position_controllers/JointGroupPositionController",
             "position_controllers/JointTrajectoryController", "position_controllers/GripperActionController",
             "velocity_controllers/JointVelocityController", "velocity_controllers/JointGroupVelocityController",
             "velocity_controllers/JointPositionController", "velocity_controllers/JointTrajectoryController",
             "effort_controllers/JointEffortController", "effort_controllers/JointGroupEffortController",
             "effort_controllers/JointPositionController", "effort_controllers/JointVelocityController",
             "effort_controllers/JointGroupPositionController", "effort_controllers/JointTrajectoryController",
             "effort_controllers/GripperActionController",
             "pos_vel_controllers/JointTrajectoryController", "pos_vel_acc_controllers/JointTrajectoryController",
             "diff_drive_controller/DiffDriveController", "ackermann_steering_controller/AckermannSteeringController",
             "four_wheel_steering_controller/FourWheelSteeringController",
             "force_torque_sensor_controller/ForceTorqueSensorController",
             "imu_sensor_controller/ImuSensorController"})
      t[name] = kRosControllers;
    for (const char* name : {
             "joint_state_broadcaster/JointStateBroadcaster", "joint_trajectory_controller/JointTrajectoryController",
             "forward_command_controller/ForwardCommandController",
             "forward_command_controller/MultiInterfaceForwardCommandController",
             "diff_drive_controller/DiffDriveController",
             "gripper_controllers/GripperActionController",
             "parallel_gripper_action_controller/GripperActionController",
             "imu_sensor_broadcaster/IMUSensorBroadcaster",
             "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster",
             "range_sensor_broadcaster/RangeSensorBroadcaster",
             "pid_controller/PidController",
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

}  // namespace lcm_control::cm
