#include "controller_manager/controller.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "bus/messages.hpp"
#include "controller_manager/claims.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"

namespace lcm_control::cm {

JointData* ControllerContext::export_reference(const std::string& dof, std::vector<Interface> interfaces,
                                               const JointData* state_from) {
  JointData& r = hw_.export_reference(name_, dof, std::move(interfaces), state_from);
  if (self_) self_->exported_.push_back(&r);
  return &r;
}

JointData* ControllerContext::claim(const std::string& joint, Interface iface) {
  if (JointData* r = hw_.reference(joint)) {  // chaining: another controller's reference interface
    if (r->exported_by == name_)
      throw ControllerError(fmt::format("controller '{}' cannot claim its own reference interface '{}'", name_, joint));
    if (!r->live && !checking_)
      throw ControllerError(fmt::format("controller '{}': '{}' is a reference interface of controller '{}', which is "
                                        "not loaded: load '{}' first (the spawner loads in the order given)",
                                        name_, joint, r->exported_by, r->exported_by));
    if (std::find(r->offered.begin(), r->offered.end(), iface) == r->offered.end()) {
      std::vector<std::string> offered;
      for (const Interface i : r->offered) offered.push_back(quantity_of(i));
      throw InterfaceError(fmt::format("controller '{}': reference interface '{}' of controller '{}' takes {}, not {}",
                                       name_, joint, r->exported_by, fmt::join(offered, ", "), quantity_of(iface)));
    }
    if (self_) {
      Claim& c = self_->claim_;
      if (!c.interface) c.joints.clear();
      if (!c.interface) c.interface = iface;
      c.joints.push_back(joint);
      c.interfaces.push_back(iface);
    }
    return r;
  }
  const std::string slash_owner = joint.substr(0, joint.find('/'));
  if (joint.find('/') != std::string::npos && !model_.joint(joint))
    for (const auto& spec : model_.controllers)
      if (spec.name == slash_owner)
        throw ControllerError(fmt::format("controller '{}': '{}' names controller '{}', which has exported no "
                                          "reference interface '{}': load '{}' first, or check that it is a chainable "
                                          "type with '{}' among its dofs",
                                          name_, joint, slash_owner, joint, slash_owner,
                                          joint.substr(joint.find('/') + 1)));
  const std::string why = check_interface(model_, name_, joint, iface);
  if (!why.empty()) {
    if (model_.joint(joint)) throw InterfaceError(why);
    throw ControllerError(why);
  }
  JointData* j = hw_.find(joint);
  if (!j) throw ControllerError(fmt::format("controller '{}': joint '{}' has no hardware handle", name_, joint));
  if (self_) {
    Claim& c = self_->claim_;
    if (!c.interface) c.joints.clear();  // joints it only read were listed while it claimed nothing
    if (!c.interface) c.interface = iface;
    c.joints.push_back(joint);
    c.interfaces.push_back(iface);
  }
  uses(j->component, true);
  return j;
}

const JointData* ControllerContext::read(const std::string& joint, const std::string& key,
                                         const std::string& listed_as) {
  JointData* j = hw_.find(joint);
  if (!j) {
    std::string all;
    for (const auto& x : hw_.joints()) all += (all.empty() ? "" : ", ") + x.name;
    throw params_.error(key, fmt::format("joint '{}' has no transmission in {}, so no state (actuated joints: {})",
                                         joint, model_.urdf_path, all));
  }
  if (self_ && !self_->claim_.interface) self_->claim_.joints.push_back(listed_as.empty() ? joint : listed_as);
  uses(j->component, false);
  return j;
}

void ControllerContext::uses(int component, bool commands) {
  if (!self_ || component < 0) return;
  std::vector<int>& list = commands ? self_->uses_.commands : self_->uses_.reads;
  if (std::find(list.begin(), list.end(), component) == list.end()) list.push_back(component);
}

ControllerError ControllerContext::not_a_gpio(const std::string& name, const std::string& key, const char* kind,
                                              bool GpioData::*has) const {
  std::vector<std::string> names;
  for (const GpioData& d : hw_.gpios())
    if (d.*has) names.push_back(d.name);
  return params_.error(key, fmt::format("'{}' is not a <gpio> {} interface of {} (its {} interfaces: {})", name, kind,
                                        model_.urdf_path, kind,
                                        names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

GpioData* ControllerContext::claim_gpio(const std::string& name, const std::string& key) {
  GpioData* g = hw_.gpio(name);
  if (!g || !g->has_command) throw not_a_gpio(name, key, "command", &GpioData::has_command);
  if (self_) self_->claim_.gpios.push_back(name);
  uses(g->component, true);
  return g;
}

const GpioData* ControllerContext::read_gpio(const std::string& name, const std::string& key) {
  const GpioData* g = hw_.gpio(name);
  if (!g || !g->has_state) throw not_a_gpio(name, key, "state", &GpioData::has_state);
  uses(g->component, false);
  return g;
}

const SensorData* ControllerContext::sensor(const std::string& name, const std::string& key, SensorKind kind) {
  const SensorData* s = hw_.sensor(name);
  if (s && s->kind == kind) {
    uses(s->component, false);
    return s;
  }
  std::vector<std::string> same_kind, all;
  for (const SensorSpec& x : model_.sensors) {
    all.push_back(fmt::format("{} ({}{})", x.name, to_string(x.kind), x.simulated() ? "" : ", not simulated"));
    if (x.kind == kind && x.simulated()) same_kind.push_back(x.name);
  }
  const SensorSpec* spec = nullptr;
  for (const SensorSpec& x : model_.sensors)
    if (x.name == name) spec = &x;
  std::string why;
  if (spec && spec->kind != kind)
    why = fmt::format("sensor '{}' is {}, not {}", name, to_string(spec->kind), to_string(kind));
  else if (spec)
    why = fmt::format("sensor '{}' is not simulated: {}", name, spec->not_simulated);
  else
    why = fmt::format("{} declares no sensor '{}'", model_.urdf_path, name);
  throw params_.error(key, fmt::format("{} ({} sensors: {})", why, to_string(kind),
                                       same_kind.empty() ? "none" : fmt::format("{}", fmt::join(same_kind, ", "))));
}

std::vector<std::string> ControllerContext::actuated_joints() const { return model_.actuated_joints(); }

void ControllerContext::take_commands(bool array, size_t width, std::function<void(const double* values)> set) {
  if (!self_) throw ControllerError(fmt::format("controller '{}': take_commands() outside init()", name_));
  Controller* c = self_;
  const std::string name = name_;
  auto bad = [c, name](const std::string& why) {
    if (c->dropped_++ % 100 == 0)
      spdlog::warn("{}: dropped a command: {} ({} dropped so far)", name, why, c->dropped_);
  };
  c->input_ = CommandInput{array, width, set};
  if (array) {
    endpoints_.subscribe<float64_array_t>(
        channel("command"),
        [bad, width, set](const float64_array_t& m) {
          if (static_cast<size_t>(m.size) != width) return bad(fmt::format("{} values for {} joints", m.size, width));
          const std::string why = check(m);
          if (!why.empty()) return bad(why);
          set(m.data.data());
        },
        bad);
  } else {
    endpoints_.subscribe<float64_t>(
        channel("command"),
        [bad, set](const float64_t& m) {
          if (!std::isfinite(m.data)) return bad("NaN or Inf");
          set(&m.data);
        },
        bad);
  }
}

}  // namespace lcm_control::cm
