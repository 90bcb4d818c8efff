#include "bus/messages.hpp"

#include <fmt/format.h>

namespace lcm_control {

namespace {
template <class V>
bool sized(const V& v, int n) {
  return n >= 0 && static_cast<int>(v.size()) == n;
}
}  // namespace

std::string check(const joint_state_t& m) {
  const int n = m.num_joints;
  if (!sized(m.name, n) || !sized(m.position, n) || !sized(m.velocity, n) || !sized(m.effort, n))
    return fmt::format("num_joints {} does not match the arrays ({} names, {} positions, {} velocities, {} efforts)", n,
                       m.name.size(), m.position.size(), m.velocity.size(), m.effort.size());
  return "";
}

std::string check(const hardware_state_t& m) {
  const int n = m.num_actuators;
  if (!sized(m.name, n) || !sized(m.mode, n) || !sized(m.position, n) || !sized(m.velocity, n) || !sized(m.effort, n))
    return fmt::format("num_actuators {} does not match the arrays", n);
  if (!all_finite(m.position) || !all_finite(m.velocity) || !all_finite(m.effort)) return "contains NaN or Inf";
  if (!sized(m.sensor_interface, m.num_sensor_values) || !sized(m.sensor_value, m.num_sensor_values))
    return fmt::format("num_sensor_values {} does not match the arrays", m.num_sensor_values);
  if (!all_finite(m.sensor_value)) return "a sensor value is NaN or Inf";
  if (!sized(m.error_component, m.num_component_errors) || !sized(m.error_reason, m.num_component_errors))
    return fmt::format("num_component_errors {} does not match the arrays", m.num_component_errors);
  return "";
}

std::string check(const hardware_command_t& m) {
  const int n = m.num_actuators;
  if (!sized(m.name, n) || !sized(m.mode, n) || !sized(m.command, n) || !sized(m.damping, n))
    return fmt::format("num_actuators {} does not match the arrays", n);
  for (int k = 0; k < n; ++k) {
    if (m.mode[k] < hardware_command_t::MODE_NONE || m.mode[k] > hardware_command_t::MODE_EFFORT)
      return fmt::format("actuator '{}' has unknown mode {}", m.name[k], int(m.mode[k]));
    if (m.mode[k] != hardware_command_t::MODE_NONE && !std::isfinite(m.command[k]))
      return fmt::format("actuator '{}' command is NaN or Inf", m.name[k]);
    if (m.mode[k] == hardware_command_t::MODE_EFFORT && !(m.damping[k] >= 0 && std::isfinite(m.damping[k])))
      return fmt::format("actuator '{}' damping {} is not a finite value >= 0", m.name[k], m.damping[k]);
  }
  if (!sized(m.gpio_interface, m.num_gpio_commands) || !sized(m.gpio_command, m.num_gpio_commands))
    return fmt::format("num_gpio_commands {} does not match the arrays", m.num_gpio_commands);
  for (int k = 0; k < m.num_gpio_commands; ++k)
    if (!std::isfinite(m.gpio_command[k]))
      return fmt::format("gpio command '{}' is NaN or Inf", m.gpio_interface[size_t(k)]);
  if (!sized(m.component, m.num_components) || !sized(m.component_state, m.num_components))
    return fmt::format("num_components {} does not match the arrays", m.num_components);
  for (int k = 0; k < m.num_components; ++k)
    if (m.component_state[size_t(k)] < hardware_command_t::COMPONENT_UNCONFIGURED ||
        m.component_state[size_t(k)] > hardware_command_t::COMPONENT_FINALIZED)
      return fmt::format("component '{}' has unknown state {}", m.component[size_t(k)], int(m.component_state[size_t(k)]));
  return "";
}

std::string check(const float64_array_t& m) {
  if (!sized(m.data, m.size)) return fmt::format("size {} does not match data ({} values)", m.size, m.data.size());
  if (!all_finite(m.data)) return "contains NaN or Inf";
  return "";
}

void resize(joint_state_t& m, int n) {
  m.num_joints = n;
  m.name.resize(n);
  m.position.resize(n);
  m.velocity.resize(n);
  m.effort.resize(n);
}

void resize(hardware_state_t& m, int n) {
  m.num_sensor_values = int32_t(m.sensor_value.size());  // the sensors stay as they are
  m.sensor_interface.resize(m.sensor_value.size());
  m.num_component_errors = int32_t(m.error_reason.size());  // so do the errors
  m.error_component.resize(m.error_reason.size());
  m.num_actuators = n;
  m.name.resize(n);
  m.mode.resize(n);
  m.position.resize(n);
  m.velocity.resize(n);
  m.effort.resize(n);
}

void resize(hardware_command_t& m, int n) {
  m.num_gpio_commands = int32_t(m.gpio_command.size());  // the GPIO commands stay as they are
  m.gpio_interface.resize(m.gpio_command.size());
  m.num_components = int32_t(m.component_state.size());
  m.component.resize(m.component_state.size());
  m.num_actuators = n;
  m.name.resize(n);
  m.mode.resize(n);
  m.command.resize(n);
  m.damping.resize(n);
}

PidGains gains_of(const pid_gains_t& m) {
  return PidGains{m.p, m.i, m.d, m.i_clamp_min, m.i_clamp_max, m.antiwindup != 0};
}

void set_gains(pid_gains_t& m, const PidGains& g) {
  m.p = g.p;
  m.i = g.i;
  m.d = g.d;
  m.i_clamp_min = g.i_clamp_min;
  m.i_clamp_max = g.i_clamp_max;
  m.antiwindup = g.antiwindup;
}

cm_request_t cm_request(int8_t op, std::vector<std::string> names, std::vector<std::string> start,
                        std::vector<std::string> stop, int8_t strictness) {
  cm_request_t r{};
  r.op = op;
  r.num_names = int32_t(names.size());
  r.names = std::move(names);
  r.num_start = int32_t(start.size());
  r.start = std::move(start);
  r.num_stop = int32_t(stop.size());
  r.stop = std::move(stop);
  r.strictness = strictness;
  return r;
}

}  // namespace lcm_control
