#include "description/load.hpp"

#include <fmt/format.h>

#include <filesystem>

#include "description/control_config.hpp"
#include "description/model_check.hpp"
#include "description/urdf_reader.hpp"

namespace lcm_control {

RobotModel load_robot_model(const std::string& urdf_path, const std::string& config_path, const LoadOptions& options) {
  return load_robot_model(urdf_path, config_path.empty() ? std::vector<std::string>{} : std::vector{config_path},
                          options);
}

RobotModel load_robot_model(const std::string& urdf_path, const std::vector<std::string>& config_paths,
                            const LoadOptions& options) {
  RobotModel model;
  model.options = options;
  std::vector<std::string> problems;
  bool parsed = true;
  try {
    read_urdf(model, urdf_path, options, problems);
  } catch (const ModelError& e) {
    parsed = false;
    problems.insert(problems.end(), e.problems().begin(), e.problems().end());
  }
  model.ns = robot_namespace(options.ns, model.gazebo_plugin_namespace);
  if (options.ns.empty() && !model.ns.empty())
    model.notes.push_back(fmt::format("{}: namespace '{}' from the gazebo_ros_control plugin's <robotNamespace>; "
                                      "channels are {}/... (give the tools --namespace {})",
                                      urdf_path, model.ns, model.ns, model.ns));
  std::vector<std::string> configs = config_paths;
  if (configs.empty() && parsed && options.config_from_plugin) {  // as gz_ros2_control: the plugin's <parameters>
    for (const auto& written : model.ros2_control_plugin.parameters) {
      namespace fs = std::filesystem;
      // Relative: to the working directory, as gz_ros2_control passes it on; else beside the URDF.
      const fs::path beside = fs::path(urdf_path).parent_path() / written;
      const std::string p = fs::is_regular_file(written) || fs::path(written).is_absolute() ? written : beside.string();
      if (fs::is_regular_file(p)) {
        configs.push_back(p);
        model.notes.push_back(fmt::format("{}: controllers from the {} plugin's <parameters> {} (no --config given)",
                                          urdf_path, model.ros2_control_plugin.filename, p));
      } else {
        model.warnings.push_back(fmt::format("{}: the {} plugin's <parameters> names {}, which is not a file; no "
                                             "controllers read from it (give --config)",
                                             urdf_path, model.ros2_control_plugin.filename, written));
      }
    }
  }
  if (!configs.empty()) {
    try {
      load_control_config_into(model, configs);
    } catch (const ModelError& e) {
      parsed = false;
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
    }
  }
  if (parsed) check_model(model, problems);
  if (!problems.empty()) throw ModelError(problems);
  return model;
}

}  // namespace lcm_control
