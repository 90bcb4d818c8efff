#include "controller_manager/hardware.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "bus/hardware_wire.hpp"
#include "controller_interface/controller.hpp"

namespace lcm_control::cm {

Hardware::Hardware(const RobotModel& model) {
  for (const auto& t : model.transmissions) {
    JointData j;
    j.name = t.joint;
    j.actuator = t.actuator;
    j.urdf = model.joint(t.joint);
    j.map = t.map;
    j.offered = t.interfaces;
    j.any_interface = t.any_interface;
    j.continuous = j.urdf && j.urdf->type == JointType::Continuous;
    joints_.push_back(j);
  }
  actuator_of_joint_.assign(joints_.size(), -1);
  for (const SensorSpec& spec : model.sensors) {
    if (!spec.simulated()) continue;
    SensorData d;
    d.name = spec.name;
    d.kind = spec.kind;
    d.frame_id = spec.frame_id.empty() ? spec.link : spec.frame_id;
    d.values.assign(sensor_interfaces(spec.kind).size(), NAN);
    sensors_.push_back(std::move(d));
  }
  const GpioInterfaces g = gpio_interfaces(model.ros2_control);
  for (const auto& name : g.states) gpios_.push_back(GpioData{name, true, false, NAN, NAN, nullptr});
  for (const auto& name : g.commands) {
    if (GpioData* d = gpio(name))
      d->has_command = true;
    else
      gpios_.push_back(GpioData{name, false, true, NAN, NAN, nullptr});
  }
  gpio_slot_.assign(gpios_.size(), -1);
  std::vector<HardwareComponent> components = hardware_components(model);
  const std::vector<Lifecycle> states = initial_component_states(model, components);
  for (size_t k = 0; k < components.size(); ++k) {
    const int index = int(k);
    const HardwareComponent& c = components[k];
    for (const std::string& joint : c.joints)
      if (JointData* j = find(joint)) j->component = index;
    for (SensorData& s : sensors_)
      if (std::find(c.sensors.begin(), c.sensors.end(), s.name) != c.sensors.end()) s.component = index;
    for (GpioData& g : gpios_)
      if (std::find(c.gpios.begin(), c.gpios.end(), g.name.substr(0, g.name.find('/'))) != c.gpios.end())
        g.component = index;
    ComponentData d;
    d.info = std::move(components[k]);
    d.state = states[k];
    components_.push_back(std::move(d));
  }
}

int Hardware::component_index(const std::string& name) const {
  for (size_t k = 0; k < components_.size(); ++k)
    if (components_[k].info.name == name) return int(k);
  return -1;
}

GpioData* Hardware::gpio(const std::string& name) {
  for (GpioData& d : gpios_)
    if (d.name == name) return &d;
  return nullptr;
}

const SensorData* Hardware::sensor(const std::string& name) const {
  for (const SensorData& s : sensors_)
    if (s.name == name) return &s;
  return nullptr;
}

std::vector<std::string> Hardware::missing_sensors() const {
  std::vector<std::string> out;
  for (const SensorData& s : sensors_)
    if (!s.present) out.push_back(s.name);
  return out;
}

JointData* Hardware::find(const std::string& joint) {
  for (auto& j : joints_)
    if (j.name == joint) return &j;
  return reference(joint);
}

JointData* Hardware::reference(const std::string& name) {
  for (auto& r : references_)
    if (r.name == name) return &r;
  return nullptr;
}

JointData& Hardware::export_reference(const std::string& controller, const std::string& dof,
                                      std::vector<Interface> offered, const JointData* mirror) {
  const std::string name = controller + "/" + dof;
  JointData* r = reference(name);
  if (!r) {
    references_.emplace_back();
    r = &references_.back();
    r->name = name;
    r->exported_by = controller;
  }
  r->offered = std::move(offered);
  r->any_interface = true;
  r->mirror = mirror;
  r->urdf = mirror ? mirror->urdf : nullptr;
  r->continuous = mirror && mirror->continuous;
  return *r;
}

void Hardware::set_references_live(const std::string& controller, bool live) {
  for (auto& r : references_)
    if (r.exported_by == controller) {
      r.live = live;
      r.command = 0;
      r.owner = nullptr;
    }
}

std::vector<const JointData*> Hardware::references_of(const std::string& controller) const {
  std::vector<const JointData*> out;
  for (const auto& r : references_)
    if (r.exported_by == controller && r.live) out.push_back(&r);
  return out;
}

std::string Hardware::bind(const hardware_state_t& state, hardware_command_t& command) {
  bound_ = false;
  std::vector<std::string> ours;
  for (const JointData& j : joints_) ours.push_back(j.actuator);
  const ActuatorBinding b = bind_actuators(ours, state.name);
  actuator_of_joint_ = b.slot;
  std::vector<std::string> problems;
  for (size_t k = 0; k < joints_.size(); ++k) {
    const JointData& j = joints_[k];
    const int a = actuator_of_joint_[k];
    if (a < 0) {
      problems.push_back(fmt::format("actuator '{}' (joint '{}') is missing", j.actuator, j.name));
      continue;
    }
    // ROS 1 transmissions: the hardware takes the first interface; a <ros2_control> joint: any it offers.
    const size_t n_taken = j.any_interface ? j.offered.size() : 1;
    std::vector<std::string> taken;
    bool takes = false;
    for (size_t i = 0; i < n_taken; ++i) {
      takes = takes || state.mode[a] == wire_mode(j.offered[i]);
      taken.push_back(to_string(j.offered[i]));
    }
    if (!takes)
      problems.push_back(fmt::format("actuator '{}' takes {} commands but the URDF says joint '{}' takes {}",
                                     j.actuator, wire_mode_name(state.mode[a]), j.name, fmt::join(taken, " or ")));
  }
  if (!b.repeated.empty()) problems.push_back(b.problem(true));
  if (!problems.empty()) {
    std::string s = "hardware does not match the URDF: ";
    for (size_t k = 0; k < problems.size(); ++k) s += (k ? "; " : "") + problems[k];
    return s;
  }
  const int n = state.num_actuators;
  command.num_actuators = n;
  command.name = state.name;
  command.mode.assign(n, hardware_command_t::MODE_NONE);
  command.command.assign(n, 0.0);
  command.damping.assign(n, 0.0);
  sensor_slot_.clear();
  for (SensorData& d : sensors_) {
    d.present = true;
    for (const std::string& i : sensor_interfaces(d.kind)) {
      const std::string name = d.name + "/" + i;
      int slot = -1;
      for (int k = 0; k < state.num_sensor_values && slot < 0; ++k)
        if (state.sensor_interface[k] == name) slot = k;
      sensor_slot_.push_back(slot);
      d.present = d.present && slot >= 0;
    }
    std::fill(d.values.begin(), d.values.end(), NAN);
  }
  size_t n_commands = 0;
  for (size_t k = 0; k < gpios_.size(); ++k) {
    gpio_slot_[k] = -1;
    for (int v = 0; v < state.num_sensor_values && gpios_[k].has_state && gpio_slot_[k] < 0; ++v)
      if (state.sensor_interface[size_t(v)] == gpios_[k].name) gpio_slot_[k] = v;
    gpios_[k].state = NAN;
    if (gpios_[k].has_command) ++n_commands;
  }
  command.gpio_interface.reserve(n_commands);  // write() lists the commanded ones; it does not allocate
  command.gpio_command.reserve(n_commands);
  command.component.clear();  // every name now, so that write() only sets the states and the count
  for (const ComponentData& c : components_) command.component.push_back(c.info.name);
  command.component_state.assign(components_.size(), hardware_command_t::COMPONENT_ACTIVE);
  command.num_components = 0;
  session_ = state.session;
  bound_ = true;
  return "";
}

void Hardware::read(const hardware_state_t& s) {
  for (size_t k = 0; k < joints_.size(); ++k) {
    JointData& j = joints_[k];
    const int a = actuator_of_joint_[k];
    j.position = j.map.actuator_to_joint_position(s.position[a]);
    j.velocity = j.map.actuator_to_joint_velocity(s.velocity[a]);
    j.effort = j.map.actuator_to_joint_effort(s.effort[a]);
  }
  size_t v = 0;
  for (SensorData& d : sensors_)
    for (double& x : d.values) {
      const int slot = sensor_slot_[v++];
      if (slot >= 0 && slot < s.num_sensor_values) x = s.sensor_value[size_t(slot)];
    }
  for (size_t k = 0; k < gpios_.size(); ++k)
    if (gpio_slot_[k] >= 0 && gpio_slot_[k] < s.num_sensor_values) gpios_[k].state = s.sensor_value[size_t(gpio_slot_[k])];
  for (JointData& r : references_)
    if (r.mirror) {
      r.position = r.mirror->position;
      r.velocity = r.mirror->velocity;
      r.effort = r.mirror->effort;
    }
}

void Hardware::enforce_soft_limits(double dt, const Controller* owner) {
  for (JointData& j : joints_) {
    if (!j.owner || !j.urdf || !j.urdf->soft || (owner && j.owner != owner)) continue;
    const JointLimits l = j.urdf->limits();
    const SoftLimits& s = *j.urdf->soft;
    switch (j.owned_as) {
      case Interface::Position:
        j.command = j.soft_position.enforce(l, s, j.command, j.position, dt);
        break;
      case Interface::Velocity:
        j.command = velocity_soft_limits(l, s, j.command, j.position);
        break;
      case Interface::Effort:
        j.command = effort_soft_limits(l, s, j.command, j.position, j.velocity);
        break;
    }
  }
}

void Hardware::reset_soft_limits() {
  for (JointData& j : joints_) j.soft_position.reset();
}

void Hardware::write(const hardware_state_t& s, hardware_command_t& c) const {
  c.utime = s.utime;
  c.step = s.step;
  c.session = s.session;
  for (int a = 0; a < c.num_actuators; ++a) {
    c.mode[a] = hardware_command_t::MODE_NONE;
    c.command[a] = 0.0;
    c.damping[a] = 0.0;
  }
  bool all_active = true;
  for (size_t k = 0; k < components_.size(); ++k) {
    c.component_state[k] = static_cast<int8_t>(components_[k].state);
    all_active = all_active && components_[k].state == Lifecycle::Active;
  }
  c.num_components = all_active ? 0 : int32_t(components_.size());
  for (size_t k = 0; k < joints_.size(); ++k) {
    const JointData& j = joints_[k];
    if (!j.owner) continue;
    const int a = actuator_of_joint_[k];
    const Interface i = j.owned_as;
    double v = 0;
    switch (i) {
      case Interface::Position:
        v = j.map.joint_to_actuator_position(j.command);
        break;
      case Interface::Velocity:
        v = j.map.joint_to_actuator_velocity(j.command);
        break;
      case Interface::Effort:
        v = j.map.joint_to_actuator_effort(j.command);
        break;
    }
    if (!std::isfinite(v)) continue;  // never send a NaN: the actuator holds instead
    c.mode[a] = wire_mode(i);
    c.command[a] = v;
    if (i == Interface::Effort && j.damping > 0 && std::isfinite(j.damping))
      c.damping[a] = j.map.joint_to_actuator_damping(j.damping);
  }
  // The GPIO commands of running controllers, finite ones only; a name is written again only when the list changes.
  size_t m = 0;
  for (const GpioData& g : gpios_) {
    if (!g.owner || !std::isfinite(g.command)) continue;
    if (m == c.gpio_interface.size()) {
      c.gpio_interface.push_back(g.name);
      c.gpio_command.push_back(0.0);
    } else if (c.gpio_interface[m] != g.name) {
      c.gpio_interface[m] = g.name;
    }
    c.gpio_command[m++] = g.command;
  }
  c.gpio_interface.resize(m);
  c.gpio_command.resize(m);
  c.num_gpio_commands = int32_t(m);
}

}  // namespace lcm_control::cm
