#include "description/hardware_components.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "description/text.hpp"

namespace lcm_control {

const char* to_string(Lifecycle s) {
  switch (s) {
    case Lifecycle::Unconfigured: return "unconfigured";
    case Lifecycle::Inactive: return "inactive";
    case Lifecycle::Active: return "active";
    case Lifecycle::Finalized: return "finalized";
  }
  return "unknown";
}

std::optional<Lifecycle> lifecycle_from(const std::string& label) {
  for (Lifecycle s : {Lifecycle::Unconfigured, Lifecycle::Inactive, Lifecycle::Active, Lifecycle::Finalized})
    if (label == to_string(s)) return s;
  return std::nullopt;
}

std::string lifecycle_label(int8_t wire) {
  if (wire >= int8_t(Lifecycle::Unconfigured) && wire <= int8_t(Lifecycle::Finalized))
    return to_string(static_cast<Lifecycle>(wire));
  return fmt::format("state {} (no such state)", int(wire));
}

std::vector<HardwareComponent> hardware_components(const RobotModel& model) {
  std::vector<HardwareComponent> out;
  for (const HardwareBlock& b : model.ros2_control) {
    HardwareComponent c;
    c.name = b.name;
    c.type = b.type.empty() ? "system" : b.type;
    c.plugin = b.plugin;
    c.kind = to_string(b.kind);
    for (const TransmissionSpec& t : model.transmissions)
      if (t.hardware_block == b.name) {
        c.actuators.push_back(t.actuator);
        c.joints.push_back(t.joint);
      }
    for (const SensorSpec& s : model.sensors)
      if (s.hardware_block == b.name && s.simulated()) c.sensors.push_back(s.name);
    for (const Ros2Component& g : b.gpios) c.gpios.push_back(g.name);
    out.push_back(std::move(c));
  }
  if (model.ros2_control.empty() && !model.transmissions.empty()) {
    HardwareComponent c;
    c.name = model.name;
    c.type = "system";
    c.plugin = model.has_gazebo_ros_control_plugin ? "gazebo_ros_control/DefaultRobotHWSim" : "";
    c.kind = "simulator";
    for (const TransmissionSpec& t : model.transmissions) {
      c.actuators.push_back(t.actuator);
      c.joints.push_back(t.joint);
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::vector<Lifecycle> initial_component_states(const RobotModel& model,
                                                const std::vector<HardwareComponent>& components) {
  std::vector<Lifecycle> states(components.size(), Lifecycle::Active);
  std::vector<std::string> names, problems;
  for (const HardwareComponent& c : components) names.push_back(c.name);
  for (auto [list, state] : {std::pair{&model.components_start_unconfigured, Lifecycle::Unconfigured},
                             std::pair{&model.components_start_inactive, Lifecycle::Inactive}})
    for (const std::string& n : *list) {
      const auto at = std::find(names.begin(), names.end(), n);
      if (at == names.end()) {
        problems.push_back(fmt::format("{}: controller_manager/ros__parameters/hardware_components_initial_state/{}: "
                                       "'{}' is not a hardware component of {} (its components: {})",
                                       model.config_path, to_string(state), n, model.urdf_path,
                                       names.empty() ? "none" : join(names)));
        continue;
      }
      states[size_t(at - names.begin())] = state;
    }
  if (!problems.empty()) throw ModelError(problems);
  return states;
}

std::optional<std::vector<std::string>> lifecycle_transitions(Lifecycle from, Lifecycle to) {
  using L = Lifecycle;
  if (from == to) return std::vector<std::string>{};
  if (from == L::Finalized) return std::nullopt;
  std::vector<std::string> steps;
  if (to == L::Finalized) {
    if (from == L::Active) steps.push_back("deactivate");
    steps.push_back("shutdown");
    return steps;
  }
  const int rank_from = from == L::Unconfigured ? 0 : from == L::Inactive ? 1 : 2;
  const int rank_to = to == L::Unconfigured ? 0 : to == L::Inactive ? 1 : 2;
  const char* up[] = {"configure", "activate"};
  const char* down[] = {"cleanup", "deactivate"};
  for (int r = rank_from; r < rank_to; ++r) steps.push_back(up[r]);
  for (int r = rank_from; r > rank_to; --r) steps.push_back(down[r - 1]);
  return steps;
}

}  // namespace lcm_control
