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
             "diff_drive_controller/DiffDriveController", "tricycle_controller/TricycleController",
             "gripper_controllers/GripperActionController",
             "parallel_gripper_action_controller/GripperActionController",
             "imu_sensor_broadcaster/IMUSensorBroadcaster",
             "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster",
             "range_sensor_broadcaster/RangeSensorBroadcaster", "admittance_controller/AdmittanceController",
             "pid_controller/PidController", "ackermann_steering_controller/AckermannSteeringController",
             "bicycle_steering_controller/BicycleSteeringController",
             "tricycle_steering_controller/TricycleSteeringController",
             "mecanum_drive_controller/MecanumDriveController"})
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

const std::vector<std::string> kNone;
const std::vector<std::string> kJointStateParams = {"publish_rate", "joints", "extra_joints"};
const std::vector<std::string> kOneJointParams = {"joint"};
const std::vector<std::string> kOneJointPidParams = {"joint", "pid"};
const std::vector<std::string> kGroupParams = {"joints"};
const std::vector<std::string> kDiffDriveParams = {
    "left_wheel", "right_wheel", "wheel_separation", "wheel_radius", "wheel_separation_multiplier",
    "wheel_radius_multiplier", "left_wheel_radius_multiplier", "right_wheel_radius_multiplier", "publish_rate",
    "cmd_vel_timeout", "base_frame_id", "odom_frame_id", "enable_odom_tf", "open_loop", "velocity_rolling_window_size",
    "linear", "angular", "pose_covariance_diagonal", "twist_covariance_diagonal", "allow_multiple_cmd_vel_publishers",
    "publish_cmd", "publish_wheel_joint_controller_state", "estimate_velocity_from_position"};
const std::vector<std::string> kTrajectoryParams = {
    "joints", "gains", "velocity_ff", "constraints", "state_publish_rate", "action_monitor_rate",
    "stop_trajectory_duration", "allow_partial_joints_goal", "hold_trajectory_duration",
    // ros2_controllers
    "command_joints", "command_interfaces", "state_interfaces", "allow_integration_in_goal_trajectories",
    "open_loop_control", "interpolation_method", "allow_nonzero_velocity_at_trajectory_end", "cmd_timeout",
    "set_last_command_interface_value_as_state_on_activation", "interface_name"};

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
      {"joint_state_broadcaster/JointStateBroadcaster", "joint_state_controller/JointStateController (ROS 1 name)"},
      {"joint_trajectory_controller/JointTrajectoryController",
       "position_controllers/, velocity_controllers/ or effort_controllers/JointTrajectoryController (ROS 1 names, "
       "one per command interface)"},
      {"forward_command_controller/ForwardCommandController",
       "position_controllers/JointGroupPositionController, velocity_controllers/JointGroupVelocityController or "
       "effort_controllers/JointGroupEffortController (ROS 1 names)"},
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

const std::vector<std::string>& ros_parameters_of(const std::string& type) {
  const auto slash = type.find('/');
  const std::string cls = slash == std::string::npos ? type : type.substr(slash + 1);
  if (cls == "JointStateController") return kJointStateParams;
  if (cls == "JointTrajectoryController") return kTrajectoryParams;
  if (cls == "DiffDriveController") return kDiffDriveParams;
  if (cls == "JointGroupPositionController" && type.rfind("effort_controllers/", 0) == 0) return kGroupParams;
  if (cls.rfind("JointGroup", 0) == 0) return kGroupParams;
  if (type == "effort_controllers/JointPositionController" || type == "effort_controllers/JointVelocityController" ||
      type == "velocity_controllers/JointPositionController")
    return kOneJointPidParams;
  if (cls == "JointPositionController" || cls == "JointVelocityController" || cls == "JointEffortController")
    return kOneJointParams;
  return kNone;
}

}  // namespace lcm_control::cm
