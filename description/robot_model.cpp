#include "description/robot_model.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "description/control_config.hpp"
#include "description/model_check.hpp"
#include "description/text.hpp"
#include "description/urdf_reader.hpp"

namespace lcm_control {

ModelError::ModelError(const std::vector<std::string>& problems)
    : std::runtime_error(join(problems, "\n")), problems_(problems) {}

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Prismatic: return "prismatic";
    case JointType::Fixed: return "fixed";
    case JointType::Floating: return "floating";
    case JointType::Planar: return "planar";
  }
  return "?";
}

const char* to_string(Interface i) {
  switch (i) {
    case Interface::Position: return "PositionJointInterface";
    case Interface::Velocity: return "VelocityJointInterface";
    case Interface::Effort: return "EffortJointInterface";
  }
  return "?";
}

std::optional<Interface> parse_interface(const std::string& raw) {
  std::string n = trim(raw);
  const std::string prefix = "hardware_interface/";
  if (n.rfind(prefix, 0) == 0) n = n.substr(prefix.size());
  if (n == "PositionJointInterface") return Interface::Position;
  if (n == "VelocityJointInterface") return Interface::Velocity;
  if (n == "EffortJointInterface") return Interface::Effort;
  return std::nullopt;
}

const char* quantity_of(Interface i) {
  switch (i) {
    case Interface::Position: return "position";
    case Interface::Velocity: return "velocity";
    case Interface::Effort: return "effort";
  }
  return "?";
}

std::optional<Interface> interface_of_quantity(const std::string& name) {
  for (Interface i : {Interface::Position, Interface::Velocity, Interface::Effort})
    if (name == quantity_of(i)) return i;
  return std::nullopt;
}

const Joint* RobotModel::joint(const std::string& n) const {
  for (const auto& j : joints)
    if (j.name == n) return &j;
  return nullptr;
}
const Link* RobotModel::link(const std::string& n) const {
  for (const auto& l : links)
    if (l.name == n) return &l;
  return nullptr;
}
const TransmissionSpec* RobotModel::transmission_for_joint(const std::string& j) const {
  for (const auto& t : transmissions)
    if (t.joint == j) return &t;
  return nullptr;
}
const ControllerSpec* RobotModel::controller(const std::string& n) const {
  for (const auto& c : controllers)
    if (c.name == n) return &c;
  return nullptr;
}
std::string RobotModel::config_file_of(const std::string& key_path) const {
  if (config_key_files.empty()) return config_path;
  std::vector<std::string> files;
  auto add = [&](const std::string& f) {
    if (std::find(files.begin(), files.end(), f) == files.end()) files.push_back(f);
  };
  // The key and what is under it; else (a key no file has) its nearest parent that a file has.
  for (std::string key = key_path; files.empty();) {
    const std::string under = key + "/";
    for (const auto& [path, file] : config_key_files)
      if (path == key || path.rfind(under, 0) == 0 || under.rfind(path + "/", 0) == 0) add(file);
    const size_t slash = key.rfind('/');
    if (slash == std::string::npos) break;
    key.erase(slash);
  }
  if (files.empty()) return config_path;
  std::vector<std::string> ordered;  // in --config order
  for (const auto& f : config_paths)
    if (std::find(files.begin(), files.end(), f) != files.end()) ordered.push_back(f);
  return join(ordered, " + ");
}

std::vector<std::string> RobotModel::actuated_joints() const {
  std::vector<std::string> v;
  for (const auto& t : transmissions) v.push_back(t.joint);
  return v;
}

std::string normalize_namespace(const std::string& ns) {
  std::string out;
  for (size_t k = 0; k < ns.size(); ++k)
    if (ns[k] != '/' || (!out.empty() && out.back() != '/')) out += ns[k];
  while (!out.empty() && out.back() == '/') out.pop_back();
  return out;
}

std::string robot_namespace(const std::string& given, const std::string& plugin_namespace) {
  return normalize_namespace(given.empty() ? plugin_namespace : given);
}

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
