#include "sim_server/components.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "description/text.hpp"
#include "sim_server/gpio.hpp"

namespace lcm_control::sim {

ComponentStates::ComponentStates(const RobotModel& model) : components_(hardware_components(model)) {
  states_.assign(components_.size(), Lifecycle::Active);
  errors_.assign(components_.size(), "");
}

void ComponentStates::bind(const std::vector<std::string>& actuators) {
  component_of_.assign(actuators.size(), -1);
  for (size_t a = 0; a < actuators.size(); ++a)
    for (size_t c = 0; c < components_.size(); ++c) {
      const auto& own = components_[c].actuators;
      if (std::find(own.begin(), own.end(), actuators[a]) != own.end()) component_of_[a] = int(c);
    }
  held_.assign(actuators.size(), 0);
  for (size_t a = 0; a < held_.size(); ++a) {
    const int c = component_of_[a];
    held_[a] = c >= 0 && (states_[size_t(c)] != Lifecycle::Active || !errors_[size_t(c)].empty());
  }
}

std::vector<std::string> ComponentStates::take(const hardware_command_t& command, GpioBank& gpio) {
  std::vector<std::string> changes;
  bool changed = false;
  for (size_t c = 0; c < components_.size(); ++c) {
    Lifecycle s = Lifecycle::Active;
    for (int k = 0; k < command.num_components; ++k)
      if (command.component[size_t(k)] == components_[c].name)
        s = static_cast<Lifecycle>(command.component_state[size_t(k)]);
    if (s != Lifecycle::Active && !errors_[c].empty()) {
      changes.push_back(fmt::format("hardware component '{}': the controller manager took its error and set it {}",
                                    components_[c].name, to_string(s)));
      errors_[c].clear();
      changed = true;
    }
    if (s == states_[c]) continue;
    changes.push_back(fmt::format("hardware component '{}' is {} (was {}), as the controller manager says: {}",
                                  components_[c].name, to_string(s), to_string(states_[c]),
                                  s == Lifecycle::Active ? "its commands act again"
                                                         : "its commands are ignored and its joints held"));
    states_[c] = s;
    changed = true;
  }
  if (changed) update_holds(gpio);
  return changes;
}

std::string ComponentStates::fail(const std::string& component, const std::string& reason, GpioBank& gpio) {
  std::vector<std::string> names;
  for (size_t c = 0; c < components_.size(); ++c) {
    names.push_back(components_[c].name);
    if (components_[c].name != component) continue;
    errors_[c] = reason.empty() ? "a failure injected through sim_server/request (FAIL_COMPONENT)" : reason;
    update_holds(gpio);
    return "";
  }
  return fmt::format("there is no hardware component '{}' (the components: {})", component,
                     names.empty() ? "none" : join(names));
}

void ComponentStates::update_holds(GpioBank& gpio) {
  errors_changed_ = true;
  any_error_ = false;
  for (size_t c = 0; c < components_.size(); ++c) {
    any_error_ = any_error_ || !errors_[c].empty();
    const bool held = states_[c] != Lifecycle::Active || !errors_[c].empty();
    for (const std::string& g : components_[c].gpios) gpio.hold(g, held);
  }
  for (size_t a = 0; a < held_.size(); ++a) {
    const int c = component_of_[a];
    held_[a] = c >= 0 && (states_[size_t(c)] != Lifecycle::Active || !errors_[size_t(c)].empty());
  }
}

void ComponentStates::report(hardware_state_t& state) {
  if (!errors_changed_) return;
  errors_changed_ = false;
  state.error_component.clear();
  state.error_reason.clear();
  if (any_error_)
    for (size_t c = 0; c < components_.size(); ++c)
      if (!errors_[c].empty()) {
        state.error_component.push_back(components_[c].name);
        state.error_reason.push_back(errors_[c]);
      }
  state.num_component_errors = int32_t(state.error_component.size());
}

}  // namespace lcm_control::sim
