#include "controller_interface/controller_type.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

namespace lcm_control::cm {

const char* to_string(RosVersion v) {
  switch (v) {
    case RosVersion::Ros1: return "ROS 1";
    case RosVersion::Ros2: return "ROS 2";
    case RosVersion::Both: return "ROS 1 and ROS 2";
  }
  return "";
}

std::vector<std::string> parameter_names(const ControllerTypeInfo& info) {
  std::vector<std::string> names;
  for (const ParameterInfo& p : info.parameters)
    for (const std::string* n : {&p.name, &p.ros1, &p.ros2})
      if (!n->empty() && std::find(names.begin(), names.end(), *n) == names.end()) names.push_back(*n);
  return names;
}

namespace {
// The names the parameters `keys` give in `params` (a name or a list of names each). The entries of `strip_key`
// are "<joint>/<interface>": the joint is taken (a passthrough's `interfaces`).
std::vector<std::string> named_by(const YAML::Node& params, const std::vector<std::string>& keys,
                                  const std::string& strip_key) {
  std::vector<std::string> names;
  for (const std::string& k : keys) {
    const YAML::Node n = params.IsMap() ? params[k] : YAML::Node();
    std::vector<std::string> given;
    if (n && n.IsScalar()) given.push_back(n.Scalar());
    if (n && n.IsSequence())
      for (const YAML::Node& x : n)
        if (x.IsScalar()) given.push_back(x.Scalar());
    for (std::string& g : given) names.push_back(k == strip_key ? g.substr(0, g.rfind('/')) : g);
  }
  return names;
}
}  // namespace

std::string undeclared_claim(const ControllerTypeInfo& info, const YAML::Node& params, const Claim& claim) {
  if (info.doc.empty() && info.parameters.empty()) return "";  // a type that declares nothing (Registry::add(name, f))
  const ClaimInfo& d = info.claims;
  struct Group {
    std::vector<std::string> joints;
    std::optional<Interface> interface;  // none: any (the interface parameter chooses it)
  };
  std::vector<Group> groups;
  if (d.interface || !d.interface_param.empty())
    groups.push_back({named_by(params, d.joint_params, d.interface_param),
                      d.interface_param.empty() ? d.interface : std::nullopt});
  for (const ClaimInfo::Also& a : d.also) groups.push_back({named_by(params, a.joint_params, ""), a.interface});
  for (size_t k = 0; claim.interface && k < claim.joints.size(); ++k) {
    const std::string& joint = claim.joints[k];
    const Interface got = claim.interface_of(k);
    std::vector<std::string> declared_on;
    bool covered = false;
    for (const Group& g : groups) {
      if (std::find(g.joints.begin(), g.joints.end(), joint) == g.joints.end()) continue;
      covered = covered || !g.interface || *g.interface == got;
      declared_on.push_back(g.interface ? to_string(*g.interface) : "the interface " + d.interface_param + " names");
    }
    if (covered) continue;
    if (!declared_on.empty())
      return fmt::format("it claims '{}' on {}, which its declaration says it claims on {}", joint, to_string(got),
                         fmt::join(declared_on, " or "));
    std::vector<std::string> keys = d.joint_params;
    for (const ClaimInfo::Also& a : d.also) keys.insert(keys.end(), a.joint_params.begin(), a.joint_params.end());
    return fmt::format("it claims '{}' on {}, which no parameter its declaration names for claims ({}) gives",
                       joint, to_string(got), keys.empty() ? "none" : fmt::format("{}", fmt::join(keys, ", ")));
  }
  return "";
}

}  // namespace lcm_control::cm
