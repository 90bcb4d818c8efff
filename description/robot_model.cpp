#include "description/robot_model.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "description/text.hpp"

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

}  // namespace lcm_control
