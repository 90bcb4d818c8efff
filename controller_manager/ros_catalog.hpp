// What ROS offers that a ros_control YAML may name: controller types from
// ros_controllers, ros2_controllers and the robot vendors' packages, and the
// parameters of the types built in here. A known name that is not
// implemented is said to be so ("not implemented here"), never "does not
// exist", and a known parameter that is not supported is named as such.
#pragma once

#include <string>
#include <vector>

namespace lcm_control::cm {

// "" if `type` is not a known ROS controller type; else where it comes from (e.g. "ros_controllers",
// "franka_ros (Franka Emika)").
std::string ros_origin_of_type(const std::string& type);

// What to use here instead of a known type that is not implemented, "" if nothing comes close.
std::string ros_alternative_to(const std::string& type);

// The ROS parameters of a controller type (ROS1 and ROS2 names), for telling a real parameter that is not
// supported from a misspelt one. Empty for types not built in.
const std::vector<std::string>& ros_parameters_of(const std::string& type);

}  // namespace lcm_control::cm
