#include "controller_interface/claims.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <map>

namespace lcm_control::cm {

std::string check_interface(const RobotModel& model, const std::string& controller, const std::string& joint,
                            Interface needed) {
  const Joint* j = model.joint(joint);
  if (!j) {
    const size_t slash = joint.find('/');
    if (slash != std::string::npos && model.controller(joint.substr(0, slash)))
      return fmt::format("controller '{}': '{}' would be a reference interface of controller '{}' (ROS 2 chaining), "
                         "which exports none of that name: is it a chainable type with '{}' among its dofs?",
                         controller, joint, joint.substr(0, slash), joint.substr(slash + 1));
    std::vector<std::string> moving;
    for (const auto& x : model.joints)
      if (x.type != JointType::Fixed) moving.push_back(x.name);
    return fmt::format("controller '{}': joint '{}' is not in the URDF {} (moving joints: {})", controller, joint,
                       model.urdf_path, fmt::join(moving, ", "));
  }
  const TransmissionSpec* t = model.transmission_for_joint(joint);
  if (!t)
    return fmt::format(
        "controller '{}' needs {} on joint '{}', but the joint has no <transmission> in {} (actuated "
        "joints: {})",
        controller, to_string(needed), joint, model.urdf_path, fmt::join(model.actuated_joints(), ", "));
  std::vector<std::string> offered;
  for (Interface i : t->interfaces) offered.push_back(to_string(i));
  if (t->interfaces.front() == needed) return "";
  for (Interface i : t->interfaces)
    if (i == needed && t->any_interface) return "";  // a <ros2_control> joint: the hardware switches to it
  for (Interface i : t->interfaces)
    if (i == needed)
      return fmt::format(
          "controller '{}' needs {} on joint '{}'; transmission '{}' offers {} but the hardware takes "
          "only the first, {}",
          controller, to_string(needed), joint, t->name, fmt::join(offered, ", "), offered.front());
  std::string skipped;
  for (Interface i : t->skipped_interfaces)
    if (i == needed)
      skipped = fmt::format(" (the joint's transmission with {} is skipped: the first transmission of a joint drives "
                            "it, as in gazebo_ros_control; put the one you want first)",
                            to_string(needed));
  return fmt::format("controller '{}' needs {} on joint '{}', but transmission '{}' offers only {}{}", controller,
                     to_string(needed), joint, t->name, fmt::join(offered, ", "), skipped);
}

std::string Conflict::message() const {
  return fmt::format("controllers '{}' and '{}' would both claim {} '{}'", first, second,
                     gpio ? "GPIO interface" : "joint", joint);
}

std::optional<Conflict> find_conflict(const std::vector<std::pair<std::string, const Claim*>>& controllers) {
  std::map<std::string, std::string> owner, gpio_owner;
  for (const auto& [name, claim] : controllers) {
    for (const auto& g : claim->gpios) {
      auto [it, fresh] = gpio_owner.emplace(g, name);
      if (!fresh) return Conflict{it->second, name, g, true};
    }
    if (!claim->interface) continue;
    for (const auto& j : claim->joints) {
      auto [it, fresh] = owner.emplace(j, name);
      if (!fresh) return Conflict{it->second, name, j};
    }
  }
  return std::nullopt;
}

bool Claim::mixed() const {
  for (const Interface i : interfaces)
    if (i != interfaces.front()) return true;
  return false;
}

std::string describe(const Claim& claim) {
  if (!claim.gpios.empty())
    return fmt::format("GPIO {}{}", fmt::join(claim.gpios, ", "),
                       claim.interface ? "; " + describe(Claim{claim.interface, claim.joints, claim.interfaces, {}})
                                       : std::string());
  if (!claim.interface) return "nothing (reads state only)";
  if (!claim.mixed()) return fmt::format("{} on {}", to_string(*claim.interface), fmt::join(claim.joints, ", "));
  std::vector<std::string> parts;
  for (const Interface i : {Interface::Position, Interface::Velocity, Interface::Effort}) {
    std::vector<std::string> on;
    for (size_t k = 0; k < claim.joints.size(); ++k)
      if (claim.interface_of(k) == i) on.push_back(claim.joints[k]);
    if (!on.empty()) parts.push_back(fmt::format("{} on {}", to_string(i), fmt::join(on, ", ")));
  }
  return fmt::format("{}", fmt::join(parts, "; "));
}

}  // namespace lcm_control::cm
