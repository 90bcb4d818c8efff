// What ROS offers that a ros_control YAML may name and this project does not implement: controller types from
// ros_controllers, ros2_controllers and the robot vendors' packages. Such a name is said to be so ("not implemented
// here"), never "does not exist". The types built in here are known by their own declarations
// (controller_interface/controller_type.hpp), never listed here.
#pragma once

#include <string>
#include <vector>

#include "controller_interface/registry.hpp"

namespace lcm_control::cm {

// "" if `type` is not a known ROS controller type; else where it comes from (e.g. "ros_controllers",
// "franka_ros (Franka Emika)").
std::string ros_origin_of_type(const std::string& type);

// The exact type names the catalog knows (of ros_controllers and ros2_controllers), none of them implemented here.
std::vector<std::string> ros_catalog_types();

// What to use here instead of a known type that is not implemented, "" if nothing comes close.
std::string ros_alternative_to(const std::string& type);

// Why `type`, not in `registry`, cannot be loaded: a misspelling ("controller type 'x' does not exist; did you mean
// 'y'? Valid types: ..."), another package's known type ("... (ros_controllers) is not implemented here ..." or
// "... is not available here ..."), or an unknown one.
std::string unknown_type_message(const Registry& registry, const std::string& type);

}  // namespace lcm_control::cm
