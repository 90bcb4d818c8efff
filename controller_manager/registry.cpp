#include "controller_manager/registry.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "description/text.hpp"
#include "controller_manager/controllers/factories.hpp"
#include "controller_manager/ros_catalog.hpp"

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

void Registry::add(ControllerType type) {
  const std::string name = type.info.name;
  types_[name] = std::move(type);
}

void Registry::add(const std::string& type, Factory factory) {
  ControllerType t;
  t.info.name = type;
  t.factory = std::move(factory);
  add(std::move(t));
}

void Registry::merge(Registry&& other) {
  for (auto& [n, t] : other.types_) types_[n] = std::move(t);
}

std::unique_ptr<Controller> Registry::create(const std::string& type) const {
  auto it = types_.find(type);
  return it == types_.end() ? nullptr : it->second.factory(type);
}

const ControllerTypeInfo* Registry::info(const std::string& type) const {
  auto it = types_.find(type);
  return it == types_.end() ? nullptr : &it->second.info;
}

std::vector<std::string> Registry::types() const {
  std::vector<std::string> v;
  for (const auto& [t, x] : types_) v.push_back(t);
  return v;
}

std::string Registry::closest(const std::string& type) const {
  std::string best;
  size_t best_d = SIZE_MAX;
  const bool bare = type.find('/') == std::string::npos;
  for (const auto& [t, x] : types_) {
    size_t d = edit_distance(type, t);
    if (bare) d = std::min(d, edit_distance(type, t.substr(t.find('/') + 1)));
    if (d < best_d) best_d = d, best = t;
  }
  return best;
}

bool Registry::misspelling(const std::string& type) const {
  if (types_.empty() || has(type)) return false;
  const std::string near = closest(type);
  const bool bare = type.find('/') == std::string::npos;
  const size_t d = std::min(edit_distance(type, near), bare ? edit_distance(type, near.substr(near.find('/') + 1))
                                                             : edit_distance(type, near));
  return d <= 3 && d * 8 <= type.size();
}

std::string Registry::unknown_type_message(const std::string& type) const {
  const std::string origin = ros_origin_of_type(type);
  if (misspelling(type))
    return fmt::format("controller type '{}' does not exist; did you mean '{}'? Valid types: {}", type, closest(type),
                       join(types()));
  if (!origin.empty()) {
    const std::string instead = ros_alternative_to(type);
    const bool vendor = origin != "ros_controllers" && origin != "ros2_controllers";
    return fmt::format("controller type '{}' ({}{}) is not {} here{} (`cmctl list-types` lists the {} "
                       "implemented types)",
                       type, vendor ? "a vendor's controller, " : "", origin, vendor ? "available" : "implemented",
                       instead.empty() ? "" : "; use " + instead, types().size());
  }
  const std::string why = type.find('/') == std::string::npos
                              ? "no controller of this project is named so"
                              : fmt::format("package '{}' is not one whose controllers this project implements",
                                            type.substr(0, type.find('/')));
  return fmt::format("controller type '{}' is not available here: {} (`cmctl list-types` lists the {} implemented "
                     "types; a controller of your own is a plugin: user guide section 15)",
                     type, why, types().size());
}

}  // namespace lcm_control::cm
