// The built-in controller types, each declared with its factory in its family's file in controllers/: a family's
// function takes what tells its types apart (the interface, one joint or a group), and registry.cpp registers each
// type in one line.
#pragma once

#include "controller_interface/controller.hpp"
#include "controller_interface/controller_type.hpp"

namespace lcm_control::cm {

ControllerType joint_state_controller();
ControllerType joint_state_broadcaster();  // ROS 2
ControllerType franka_state_controller();
// `command` on one joint (a float64_t) or, with `group`, on `joints` (a float64_array_t).
ControllerType forward_command_controller(Interface command, bool group);
// ROS 2's: the interface from interface_name (`joints`) or interface_names (one, on `joint`).
ControllerType ros2_forward_command_controller(bool multi_interface);
// A PID from a position or a velocity set point to the `out` command of one joint.
enum class PidTarget { Position, Velocity };
ControllerType pid_controller(Interface out, PidTarget target);
ControllerType group_position_pid_controller();  // position set points to efforts, one PID per joint
// ROS 2's pid_controller/PidController: a PID per joint of dof_names to the interface command_interface names.
ControllerType ros2_pid_controller();
ControllerType joint_trajectory_controller(Interface command);
ControllerType ros2_joint_trajectory_controller();  // the interface from command_interfaces
ControllerType diff_drive_controller();
// ros2_controllers' steering drives (steering_controllers_library), tricycle_controller, and the holonomic bases.
enum class SteeringKind { Bicycle, Tricycle, Ackermann };
ControllerType steering_controller(SteeringKind kind);
ControllerType tricycle_controller();
ControllerType mecanum_drive_controller();
ControllerType omni_wheel_drive_controller();
ControllerType gpio_command_controller();  // gpio_controllers/GpioCommandController
ControllerType admittance_controller();     // ROS 2's admittance_controller: a tool yielding to its FT sensor (KDL)
ControllerType passthrough_controller();   // ros2_control_demos' chaining example: chainable forwarding
// gripper_command_t goals on `joint`: position or effort (ROS 1 / gripper_controllers), or ROS 2's parallel gripper.
ControllerType gripper_action_controller(Interface command, bool parallel);
// The sensors' readings (controllers/sensor_broadcasters.cpp): ROS 2's broadcasters and ROS 1's controllers.
ControllerType imu_sensor_broadcaster();
ControllerType force_torque_sensor_broadcaster();
ControllerType imu_sensor_controller();
ControllerType force_torque_sensor_controller();

}  // namespace lcm_control::cm
