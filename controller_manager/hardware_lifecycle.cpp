// The controller manager's hardware components and controllers leaving active on their own: the components' lifecycle
// (set_component_state, component errors), controllers that fail and their fallbacks, the list
// `cmctl list-hardware-components` shows, and the activity message.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "controller_manager/manager.hpp"
#include "description/text.hpp"

namespace lcm_control::cm {

namespace {
const char* const kShuttingDown = "the controller manager is shutting down";

std::string component_names(const std::vector<ComponentData>& components) {
  std::vector<std::string> names;
  for (const ComponentData& c : components) names.push_back(c.info.name);
  return names.empty() ? "none" : join_some(names, 20);
}
}  // namespace

std::string ControllerManager::unfit_to_start(const ControllerSlot& s) const {
  for (const std::string& f : s.fallbacks)
    if (!find(f))
      return fmt::format("cannot start '{}': its fallback controller '{}' is not loaded (ros2_control requires fallback "
                         "controllers configured first); load it: cmctl load {}",
                         s.name, f, f);
  const auto& components = hw_.components();
  for (const bool commands : {true, false}) {
    const auto& list = commands ? s.controller->uses().commands : s.controller->uses().reads;
    for (int k : list) {
      const ComponentData& c = components[size_t(k)];
      if (commands ? c.commandable() : c.readable()) continue;
      return fmt::format("cannot start '{}': it {} hardware component '{}', which is {}{}; {}", s.name,
                         commands ? "commands" : "reads", c.info.name, to_string(c.state),
                         c.error.empty() ? "" : " (after an error: " + c.error + ")",
                         c.state == Lifecycle::Finalized
                             ? "a finalized component comes back only when the hardware and the controller manager "
                               "restart"
                             : fmt::format("activate it first: cmctl set-hardware-component-state {} active{}",
                                           c.info.name, commands ? "" : " (or inactive)"));
    }
  }
  return "";
}

void ControllerManager::set_component_state(const std::string& name, Lifecycle target, Done done) {
  if (shutting_down_) return done({false, kShuttingDown});
  const int k = hw_.component_index(name);
  if (k < 0)
    return done({false, fmt::format("cannot set the state of hardware component '{}': there is none of that name in "
                                    "{} (its components: {})",
                                    clip(name), model_.urdf_path, component_names(hw_.components()))});
  const ComponentData& c = hw_.components()[size_t(k)];
  const auto steps = lifecycle_transitions(c.state, target);
  if (!steps)
    return done({false, fmt::format("cannot set hardware component '{}' {}: it is finalized, and a finalized "
                                    "component stays so until the hardware and the controller manager restart",
                                    name, to_string(target))});
  if (steps->empty()) return done({true, fmt::format("hardware component '{}' is already {}", name, to_string(target))});
  if (busy()) return done({false, fmt::format("cannot set hardware component '{}' {} now: a switch is being applied; "
                                              "retry",
                                              name, to_string(target))});
  std::vector<ControllerSlot*> stop;
  std::vector<std::string> stopped;
  for (const auto& s : loop_.slots())
    if (s->running && affected_by(*s->controller, k, target)) {
      stop.push_back(s.get());
      stopped.push_back(s->name);
    }
  pending_summary_ = fmt::format("hardware component '{}': {} -> {} ({}); stopped [{}]", name, to_string(c.state),
                                 to_string(target), join(*steps, ", "), join_some(stopped, 20));
  if (target == Lifecycle::Active && !c.error.empty())
    pending_summary_ += fmt::format(" (its last error: {})", c.error);
  loop_.set_pending_switch(stop, {});
  loop_.set_pending_component(k, target);
  pending_component_ = true;
  pending_done_ = std::move(done);
  if (!ticking()) {
    loop_.apply_now();
    pending_summary_ = fmt::format("{} at once ({})", pending_summary_,
                                   loop_.has_state() ? "hardware is silent" : "no hardware state received yet");
    complete_pending();
  }
}

void ControllerManager::report_failed_controllers() {
  for (const auto& s : loop_.slots()) {
    if (!s->failure) continue;
    std::vector<std::string> started, not_started;
    for (size_t f = 0; f < s->fallbacks.size(); ++f) {
      if (s->fallback_started[f]) {
        started.push_back(s->fallbacks[f]);
        continue;
      }
      const ControllerSlot* o = find(s->fallbacks[f]);
      not_started.push_back(fmt::format(
          "{} ({})", s->fallbacks[f],
          !o             ? "not loaded"
          : o->running   ? "already running"
          : !may_run(*o->controller, hw_.components()) ? "a hardware component it uses is not active"
                                                       : "a joint it claims is held by another running controller"));
    }
    spdlog::error("controller '{}' failed at step {}: {}; deactivated it{}{}{}", s->name, s->failure_step,
                  clip(s->failure), take_chain_stops(s.get()),
                  s->fallbacks.empty() ? "; it has no fallback_controllers"
                                       : fmt::format("; started its fallback controllers [{}]", join(started)),
                  not_started.empty() ? "" : fmt::format("; not started: {}", join(not_started, ", ")));
    s->failure = nullptr;
    changed();
  }
}

std::string ControllerManager::take_chain_stops(const ControllerSlot* cause) {
  std::vector<std::string> names;
  for (const auto& s : loop_.slots())
    if (s->chain_stopped_by && (!cause || s->chain_stopped_by == cause)) {
      names.push_back(s->name);
      s->chain_stopped_by = nullptr;
    }
  if (names.empty()) return "";
  return fmt::format("; and the controllers chained above it [{}] (they write its reference interfaces: a chain runs "
                     "whole, as in ros2_control)",
                     join(names));
}

void ControllerManager::report_component_errors(const hardware_state_t& st) {
  std::vector<std::string> stopped;
  for (const auto& s : loop_.slots())
    if (std::exchange(s->stopped_by_error, false)) stopped.push_back(s->name);
  const std::string chained = take_chain_stops(nullptr);
  bool any = false;
  for (ComponentData& c : hw_.components()) {
    if (!std::exchange(c.error_fresh, false)) continue;
    any = true;
    c.error = "the hardware reported an error";
    for (int e = 0; e < st.num_component_errors; ++e)
      if (st.error_component[size_t(e)] == c.info.name && !st.error_reason[size_t(e)].empty())
        c.error = clip(st.error_reason[size_t(e)]);
    spdlog::error("hardware component '{}' failed at step {}: {}; deactivated the controllers using it [{}]{}; it "
                  "is now unconfigured: once the cause is fixed, cmctl set-hardware-component-state {} active, then "
                  "start the controllers again",
                  c.info.name, c.error_step, c.error, join_some(stopped, 20), chained, c.info.name);
  }
  if (any) changed();
}

std::vector<hardware_component_t> ControllerManager::components() const {
  std::vector<hardware_component_t> out;
  const auto& components = hw_.components();
  for (size_t k = 0; k < components.size(); ++k) {
    const ComponentData& c = components[k];
    hardware_component_t m{};
    m.name = c.info.name;
    m.type = c.info.type;
    m.plugin = c.info.plugin;
    m.kind = c.info.kind;
    m.state = static_cast<int8_t>(c.state);
    m.state_label = to_string(c.state);
    m.error = c.error;
    m.joints = c.info.joints;
    for (const SensorData& s : hw_.sensors())
      if (s.component == int(k)) {
        const auto names = sensor_interfaces(s.kind);
        for (size_t i = 0; i < names.size(); ++i) {
          m.interfaces.push_back(s.name + "/" + names[i]);
          m.interface_values.push_back(s.present && i < s.values.size() ? s.values[i] : NAN);
        }
      }
    for (const GpioData& g : hw_.gpios())
      if (g.component == int(k)) {
        m.interfaces.push_back(g.name);
        m.interface_values.push_back(g.state);
      }
    for (const auto& s : loop_.slots()) {
      const auto& uses = s->controller->uses();
      if (std::find(uses.commands.begin(), uses.commands.end(), int(k)) != uses.commands.end() ||
          std::find(uses.reads.begin(), uses.reads.end(), int(k)) != uses.reads.end())
        m.controllers.push_back(s->name);
    }
    m.num_joints = int32_t(m.joints.size());
    m.num_interfaces = int32_t(m.interfaces.size());
    m.num_controllers = int32_t(m.controllers.size());
    out.push_back(std::move(m));
  }
  return out;
}

activity_t ControllerManager::activity() const {
  activity_t m{};
  m.utime = wall_us();
  m.seq = activity_seq_;
  m.step = activity_step_;
  for (const auto& s : loop_.slots()) {
    m.controller.push_back(s->name);
    m.controller_state.push_back(!from_ros2() ? s->state() : s->running ? "active" : "inactive");
  }
  for (const ComponentData& c : hw_.components()) {
    m.component.push_back(c.info.name);
    m.component_state.push_back(to_string(c.state));
  }
  m.num_controllers = int32_t(m.controller.size());
  m.num_components = int32_t(m.component.size());
  return m;
}

}  // namespace lcm_control::cm
