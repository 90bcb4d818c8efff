#include "sim_server/mock_hardware.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "bus/hardware_wire.hpp"
#include "description/text.hpp"
#include "lcm_control/hardware_command_t.hpp"

namespace lcm_control::sim {

namespace {

const HardwareBlock* block_of(const RobotModel& model, const std::string& joint) {
  for (const HardwareBlock& b : model.ros2_control)
    if (b.joint(joint)) return &b;
  return nullptr;
}

const std::string* hardware_param(const HardwareBlock& b, const std::string& key) {
  for (const auto& [k, v] : b.params)
    if (k == key) return &v;
  return nullptr;
}

// ros2_control's parse_bool: "true" in any case is true, anything else false.
bool parse_bool(const std::string& v) {
  std::string l = v;
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return l == "true";
}

}  // namespace

bool all_mock_hardware(const RobotModel& model) {
  if (model.ros2_control.empty()) return false;
  for (const HardwareBlock& b : model.ros2_control)
    if (b.kind != HardwareKind::Mock) return false;
  return true;
}

MockHardware::MockHardware(const RobotModel& model, const InitialPositions& initial) {
  std::vector<std::string> moving;
  for (const Joint& j : model.joints)
    if (j.type != JointType::Fixed && j.type != JointType::Floating && j.type != JointType::Planar) {
      joints_.push_back(JointState{j.name});
      moving.push_back(j.name);
    }
  for (const auto& [name, q] : initial) {
    if (joint_index(name) < 0) {
      const std::string near = closest_name(name, moving, 3);
      throw ModelError(fmt::format("initial position of joint '{}': {} has no moving joint of that name{}", name,
                                   model.urdf_path, near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near)));
    }
    if (!std::isfinite(q))
      throw ModelError(fmt::format("initial position of joint '{}' is {}; give a finite number", name, q));
  }
  for (JointState& s : joints_) {
    const Joint& j = *model.joint(s.name);
    const auto it = initial.find(s.name);
    const double wanted = it == initial.end() ? 0.0 : it->second;
    s.q = j.has_position_limits ? std::clamp(wanted, j.lower, j.upper) : wanted;
    if (s.q != wanted)
      start_warnings_.push_back(fmt::format("joint '{}' would start at {:g}, outside its limits [{:g}, {:g}] in {}; it "
                                            "starts at {:g}",
                                            s.name, wanted, j.lower, j.upper, model.urdf_path, s.q));
    if (j.mimic && joint_index(j.mimic->joint) >= 0)
      mimics_.push_back(MimicLink{joint_index(s.name), joint_index(j.mimic->joint), j.mimic->multiplier,
                                  j.mimic->offset});
  }
  for (const TransmissionSpec& t : model.transmissions) {
    Actuator a;
    a.name = t.actuator;
    a.joint = joint_index(t.joint);
    if (a.joint < 0)
      throw ModelError(fmt::format("{}: transmission '{}': joint '{}' is not a moving joint of the robot",
                                   model.urdf_path, t.name, t.joint));
    a.map = t.map;
    const size_t n_offered = t.any_interface ? t.interfaces.size() : 1;
    for (size_t k = 0; k < n_offered; ++k) a.offered[lcm_control::wire_mode(t.interfaces[k])] = true;
    a.wire_mode = lcm_control::wire_mode(t.interfaces.front());
    if (const HardwareBlock* b = block_of(model, t.joint)) {
      a.calculate_dynamics = demo_hardware(b->plugin);
      if (const std::string* v = hardware_param(*b, "calculate_dynamics")) a.calculate_dynamics = parse_bool(*v);
      if (const std::string* v = hardware_param(*b, "position_state_following_offset"))
        if (!parse_double(*v, a.following_offset))
          throw ModelError(fmt::format("{}:{}: ros2_control '{}': <param name=\"position_state_following_offset\"> "
                                       "'{}' is not a number; give the offset in rad or m (e.g. 0.0)",
                                       model.urdf_path, b->line, b->name, *v));
    }
    actuators_.push_back(std::move(a));
  }
  for (const MimicLink& m : mimics_) {  // a mimic starts where its joint puts it
    joints_[m.joint].q = m.multiplier * joints_[m.leader].q + m.offset;
  }
}

int MockHardware::joint_index(const std::string& name) const {
  for (size_t k = 0; k < joints_.size(); ++k)
    if (joints_[k].name == name) return int(k);
  return -1;
}

bool MockHardware::offers(int i, int8_t wire_mode) const {
  return wire_mode > 0 && wire_mode < kWireModes && actuators_[i].offered[wire_mode];
}

const char* MockHardware::mode_name(int i) const {
  switch (actuators_[i].wire_mode) {
    case hardware_command_t::MODE_POSITION: return "mock position";
    case hardware_command_t::MODE_VELOCITY: return "mock velocity";
    default: return "mock effort";
  }
}

std::string MockHardware::describe(int i) const {
  const Actuator& a = actuators_[i];
  std::string modes;
  for (int8_t w = 1; w < kWireModes; ++w)
    if (a.offered[w]) modes += fmt::format("{}{}", modes.empty() ? "" : ", ", wire_mode_name(w));
  return fmt::format("actuator '{}' -> joint '{}': mock hardware (state follows command), takes {}; "
                     "calculate_dynamics {}, position_state_following_offset {:g}; reduction {:g}, offset {:g}",
                     a.name, joint(i), modes, a.calculate_dynamics ? "true" : "false", a.following_offset,
                     a.map.reduction, a.map.offset);
}

bool MockHardware::set_command(int i, int8_t wire_mode, double value, double) {
  Actuator& a = actuators_[i];
  a.commanded = wire_mode != hardware_command_t::MODE_NONE;
  if (!a.commanded) return true;
  if (!offers(i, wire_mode)) {
    a.commanded = false;
    return false;
  }
  a.wire_mode = wire_mode;
  switch (wire_mode) {
    case hardware_command_t::MODE_POSITION: a.command = a.map.actuator_to_joint_position(value); break;
    case hardware_command_t::MODE_VELOCITY: a.command = a.map.actuator_to_joint_velocity(value); break;
    default: a.command = a.map.actuator_to_joint_effort(value); break;
  }
  return true;
}

void MockHardware::step(double dt) {
  for (Actuator& a : actuators_) {
    JointState& s = joints_[a.joint];
    if (e_stop_ || hold_all_ || !a.commanded) {
      s.qd = 0;
      s.effort = 0;
      continue;
    }
    switch (a.wire_mode) {
      case hardware_command_t::MODE_POSITION: {
        const double before = s.q;
        s.q = a.command + a.following_offset;
        if (a.calculate_dynamics) s.qd = (s.q - before) / dt;
        s.effort = 0;
        break;
      }
      case hardware_command_t::MODE_VELOCITY:
        // As GenericSystem: backward Euler on the velocity of the previous step.
        if (a.calculate_dynamics) s.q += s.qd * dt + a.following_offset;
        s.qd = a.command;
        s.effort = 0;
        break;
      default:
        s.effort = a.command;
        break;
    }
  }
  for (const MimicLink& m : mimics_) {
    joints_[m.joint].q = m.multiplier * joints_[m.leader].q + m.offset;
    joints_[m.joint].qd = m.multiplier * joints_[m.leader].qd;
    joints_[m.joint].effort = 0;
  }
}

double MockHardware::position(int i) const {
  return actuators_[i].map.joint_to_actuator_position(joints_[actuators_[i].joint].q);
}
double MockHardware::velocity(int i) const {
  return actuators_[i].map.joint_to_actuator_velocity(joints_[actuators_[i].joint].qd);
}
double MockHardware::effort(int i) const {
  return actuators_[i].map.joint_to_actuator_effort(joints_[actuators_[i].joint].effort);
}

double MockHardware::joint_position(const std::string& joint) const {
  const int k = joint_index(joint);
  return k < 0 ? NAN : joints_[k].q;
}
double MockHardware::joint_velocity(const std::string& joint) const {
  const int k = joint_index(joint);
  return k < 0 ? NAN : joints_[k].qd;
}

}  // namespace lcm_control::sim
