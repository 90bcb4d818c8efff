// A robot's files read into one checked RobotModel: the URDF or xacro (urdf_reader), the namespace, the controller
// YAML (control_config, or the gz plugin's <parameters>), then the cross-checks (model_check). Above the readers; the
// RobotModel type itself is robot_model.hpp, below them.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

// Throws ModelError naming the file and culprit of every problem.
RobotModel load_robot_model(const std::string& urdf_path, const std::vector<std::string>& config_paths,
                            const LoadOptions& options = {});
// One config file, or none for "".
RobotModel load_robot_model(const std::string& urdf_path, const std::string& config_path,
                            const LoadOptions& options = {});

}  // namespace lcm_control
