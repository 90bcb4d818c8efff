// The ros_control YAML: controller entries (name, type, parameters) and
// gazebo_ros_control/pid_gains, found as ROS finds them: at the top level, or
// under the robot's namespace (`rrbot:` for <robotNamespace>/rrbot or
// --namespace rrbot), or, when neither says, under the file's only top-level
// map that holds controllers.
#pragma once

#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "description/robot_model.hpp"

namespace lcm_control {

// Reads the config files, merged in order as rosparam loads them (a later key wins; one note per replaced key),
// into model.controllers and model.pid_gains, looking under model.ns first; $(arg NAME), $(find PKG) and $(env VAR)
// are substituted first with model.options.
void load_control_config_into(RobotModel& model, const std::vector<std::string>& config_paths);
// The same for an already parsed document (`file` is used in messages).
void parse_control_config(RobotModel& model, const YAML::Node& root, const std::string& file);
// One ros_control PID map ({p, i, d, i_clamp, i_clamp_min, i_clamp_max, antiwindup}) with
// control_toolbox's rules; `where` prefixes every problem (file and key path).
PidGains parse_pid_gains(const YAML::Node& n, const std::string& where, std::vector<std::string>& problems,
                         std::vector<std::string>& warnings);

}  // namespace lcm_control
