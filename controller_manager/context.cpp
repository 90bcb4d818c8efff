#include "controller_manager/context.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace lcm_control::cm {

JointData* HardwareContext::export_reference(const std::string& dof, std::vector<Interface> interfaces,
                                               const JointData* state_from) {
  if (!info_ || !info_->chainable)
    throw ControllerError(fmt::format("controller '{}': type '{}' exports the reference interface '{}/{}' but does "
                                      "not declare itself chainable: set `chainable` (and `references`) in its "
                                      "ControllerTypeInfo",
                                      name_, type_, name_, dof));
  JointData& r = hw_.export_reference(name_, dof, std::move(interfaces), state_from);
  record_export(&r);
  return &r;
}

JointData* HardwareContext::claim(const std::string& joint, Interface iface) {
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
    record_claim(joint, iface);
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
  record_claim(joint, iface);
  record_use(j->component, true);
  return j;
}

const JointData* HardwareContext::read(const std::string& joint, const std::string& key,
                                         const std::string& listed_as) {
  JointData* j = hw_.find(joint);
  if (!j) {
    std::string all;
    for (const auto& x : hw_.joints()) all += (all.empty() ? "" : ", ") + x.name;
    throw params_.error(key, fmt::format("joint '{}' has no transmission in {}, so no state (actuated joints: {})",
                                         joint, model_.urdf_path, all));
  }
  record_read(listed_as.empty() ? joint : listed_as);
  record_use(j->component, false);
  return j;
}

ControllerError HardwareContext::not_a_gpio(const std::string& name, const std::string& key, const char* kind,
                                              bool GpioData::*has) const {
  std::vector<std::string> names;
  for (const GpioData& d : hw_.gpios())
    if (d.*has) names.push_back(d.name);
  return params_.error(key, fmt::format("'{}' is not a <gpio> {} interface of {} (its {} interfaces: {})", name, kind,
                                        model_.urdf_path, kind,
                                        names.empty() ? "none" : fmt::format("{}", fmt::join(names, ", "))));
}

GpioData* HardwareContext::claim_gpio(const std::string& name, const std::string& key) {
  GpioData* g = hw_.gpio(name);
  if (!g || !g->has_command) throw not_a_gpio(name, key, "command", &GpioData::has_command);
  record_gpio(name);
  record_use(g->component, true);
  return g;
}

const GpioData* HardwareContext::read_gpio(const std::string& name, const std::string& key) {
  const GpioData* g = hw_.gpio(name);
  if (!g || !g->has_state) throw not_a_gpio(name, key, "state", &GpioData::has_state);
  record_use(g->component, false);
  return g;
}

const SensorData* HardwareContext::sensor(const std::string& name, const std::string& key, SensorKind kind) {
  const SensorData* s = hw_.sensor(name);
  if (s && s->kind == kind) {
    record_use(s->component, false);
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

}  // namespace lcm_control::cm
