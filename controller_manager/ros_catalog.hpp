// What ROS offers that a ros_control YAML may name: controller types from
// ros_controllers, ros2_controllers and the robot vendors' packages. A known
// name that is not implemented is said to be so ("not implemented here"),
// never "does not exist". The parameters of the types built in here are their
// own declarations' (controller_type.hpp).
#pragma once

#include <string>

namespace lcm_control::cm {

// "" if `type` is not a known ROS controller type; else where it comes from (e.g. "ros_controllers",
// "franka_ros (Franka Emika)").
std::string ros_origin_of_type(const std::string& type);

// What to use here instead of a known type that is not implemented, "" if nothing comes close.
std::string ros_alternative_to(const std::string& type);

}  // namespace lcm_control::cm
