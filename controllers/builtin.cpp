#include "controllers/builtin.hpp"

#include "controllers/factories.hpp"

namespace lcm_control::cm {

// One line per type; each is declared in its family's file in controllers/.
void register_builtin(Registry& r) {
  using I = Interface;
  r.add(joint_state_controller());
  r.add(joint_state_broadcaster());
  r.add(franka_state_controller());
  r.add(forward_command_controller(I::Position, false));
  r.add(forward_command_controller(I::Velocity, false));
  r.add(forward_command_controller(I::Effort, false));
  r.add(forward_command_controller(I::Position, true));
  r.add(forward_command_controller(I::Velocity, true));
  r.add(forward_command_controller(I::Effort, true));
  r.add(ros2_forward_command_controller(false));
  r.add(ros2_forward_command_controller(true));
  r.add(pid_controller(I::Effort, PidTarget::Position));
  r.add(pid_controller(I::Effort, PidTarget::Velocity));
  r.add(pid_controller(I::Velocity, PidTarget::Position));
  r.add(group_position_pid_controller());
  r.add(ros2_pid_controller());
  r.add(joint_trajectory_controller(I::Position));
  r.add(joint_trajectory_controller(I::Effort));
  r.add(joint_trajectory_controller(I::Velocity));
  r.add(ros2_joint_trajectory_controller());
  r.add(diff_drive_controller());
  r.add(steering_controller(SteeringKind::Bicycle));
  r.add(steering_controller(SteeringKind::Tricycle));
  r.add(steering_controller(SteeringKind::Ackermann));
  r.add(tricycle_controller());
  r.add(mecanum_drive_controller());
  r.add(omni_wheel_drive_controller());
  r.add(gpio_command_controller());
  r.add(passthrough_controller());
  r.add(admittance_controller());
  r.add(gripper_action_controller(I::Position, false));
  r.add(gripper_action_controller(I::Effort, false));
  r.add(gripper_action_controller(I::Position, true));  // parallel_gripper_action_controller/GripperActionController
  r.add(imu_sensor_broadcaster());
  r.add(force_torque_sensor_broadcaster());
  r.add(imu_sensor_controller());
  r.add(force_torque_sensor_controller());
}

const Registry& builtin_registry() {
  static const Registry r = [] {
    Registry x;
    register_builtin(x);
    return x;
  }();
  return r;
}

}  // namespace lcm_control::cm
