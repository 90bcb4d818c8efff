// The hardware components ros2_control manages, as the robot's files declare them: one per <ros2_control> block; a
// robot without blocks (URDF transmissions, ROS 1) is one component named after the robot. What each owns (its
// actuators, joints, sensors and GPIOs) and the lifecycle states it may be in (unconfigured, inactive, active,
// finalized), with the transitions ros2_control's resource manager takes between them.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

// lifecycle_msgs/State's numbers, as hardware_command_t::COMPONENT_* carries them.
enum class Lifecycle : int8_t { Unconfigured = 1, Inactive = 2, Active = 3, Finalized = 4 };
const char* to_string(Lifecycle s);                       // "unconfigured", ...
std::optional<Lifecycle> lifecycle_from(const std::string& label);  // the four labels; nullopt for anything else
// A state as hardware_command_t / cm_request_t carry it: "inactive", ... or "state N (no such state)".
std::string lifecycle_label(int8_t wire);

struct HardwareComponent {
  std::string name;
  std::string type;    // system | actuator | sensor
  std::string plugin;  // <hardware><plugin>; for a robot without blocks, its Gazebo plugin ("" none)
  std::string kind;    // "simulator" or "mock"
  std::vector<std::string> actuators;  // hardware message names, in transmission order
  std::vector<std::string> joints;     // the actuated joints, same order
  std::vector<std::string> sensors;    // sensor names (a sensor outside every block belongs to none)
  std::vector<std::string> gpios;      // <gpio> names
};

// In <ros2_control> block order; one component when the robot has no blocks but has transmissions; none for a robot
// with neither.
std::vector<HardwareComponent> hardware_components(const RobotModel& model);

// Each component's state at start: active, unless the parameter file's controller_manager
// hardware_components_initial_state lists it under unconfigured or inactive. Throws ModelError naming the key and the
// components there are for a name that is none of them.
std::vector<Lifecycle> initial_component_states(const RobotModel& model,
                                                const std::vector<HardwareComponent>& components);

// The transitions ros2_control takes from `from` to `to` ("configure", "activate", "deactivate", "cleanup",
// "shutdown"), empty when already there; nullopt when there is no way (a finalized component stays finalized).
std::optional<std::vector<std::string>> lifecycle_transitions(Lifecycle from, Lifecycle to);

}  // namespace lcm_control
