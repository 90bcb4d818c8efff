#include "controller_manager/controller_type.hpp"

#include <algorithm>

namespace lcm_control::cm {

const char* to_string(RosVersion v) {
  switch (v) {
    case RosVersion::Ros1: return "ROS 1";
    case RosVersion::Ros2: return "ROS 2";
    case RosVersion::Both: return "ROS 1 and ROS 2";
  }
  return "";
}

std::vector<std::string> parameter_names(const ControllerTypeInfo& info) {
  std::vector<std::string> names;
  for (const ParameterInfo& p : info.parameters)
    for (const std::string* n : {&p.name, &p.ros1, &p.ros2})
      if (!n->empty() && std::find(names.begin(), names.end(), *n) == names.end()) names.push_back(*n);
  return names;
}

}  // namespace lcm_control::cm
