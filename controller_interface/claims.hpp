// Who owns which joint on which interface. ROS's rule, kept exactly: a joint
// belongs to at most one running controller, whatever the interfaces, and the
// check is strict whatever the switch's strictness. State readers claim nothing.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control::cm {

// The joints a controller commands and the interface it needs on each; no interface for state readers
// (joint_state_controller), which claim nothing and list the joints they read.
struct Claim {
  std::optional<Interface> interface;  // the first joint's: what the controller's command numbers set
  std::vector<std::string> joints;
  std::vector<Interface> interfaces;   // per claimed joint (a car's wheels on velocity, its steering on position)
  std::vector<std::string> gpios;      // <gpio> command interfaces it commands, "<gpio>/<interface>"
  Interface interface_of(size_t k) const { return k < interfaces.size() ? interfaces[k] : interface.value(); }
  bool mixed() const;                  // not every joint on the same interface
};

// "" when `joint` can be commanded on `needed` (a URDF <transmission>: its first
// interface, as gazebo_ros_control; a <ros2_control> joint: any of its command
// interfaces), else a message naming the controller, the joint, the interface
// needed and the interfaces offered.
std::string check_interface(const RobotModel& model, const std::string& controller, const std::string& joint,
                            Interface needed);

struct Conflict {
  std::string first, second, joint;
  bool gpio = false;             // `joint` is a GPIO command interface
  std::string message() const;  // "controllers 'a' and 'b' would both claim joint 'j'"
};

// The first joint claimed by two of `controllers` (name, claim), in list order.
std::optional<Conflict> find_conflict(const std::vector<std::pair<std::string, const Claim*>>& controllers);

// "PositionJointInterface on j1, j2" or "nothing (reads joint state only)".
std::string describe(const Claim& claim);

}  // namespace lcm_control::cm
