#include "controller_manager/controller.hpp"

#include <fmt/format.h>

#include "controller_manager/claims.hpp"

namespace lcm_control::cm {

JointData* ControllerContext::claim(const std::string& joint, Interface iface) {
  const std::string why = check_interface(model_, name_, joint, iface);
  if (!why.empty()) {
    if (model_.joint(joint)) throw InterfaceError(why);
    throw ControllerError(why);
  }
  JointData* j = hw_.find(joint);
  if (!j) throw ControllerError(fmt::format("controller '{}': joint '{}' has no hardware handle", name_, joint));
  if (self_) {
    if (self_->claim_.interface && *self_->claim_.interface != iface)
      throw ControllerError(fmt::format("controller '{}' claims both {} and {}", name_,
                                        to_string(*self_->claim_.interface), to_string(iface)));
    self_->claim_.interface = iface;
    self_->claim_.joints.push_back(joint);
  }
  return j;
}

const JointData* ControllerContext::read(const std::string& joint, const std::string& key) {
  JointData* j = hw_.find(joint);
  if (!j) {
    std::string all;
    for (const auto& x : hw_.joints()) all += (all.empty() ? "" : ", ") + x.name;
    throw params_.error(key, fmt::format("joint '{}' has no transmission in {}, so no state (actuated joints: {})",
                                         joint, model_.urdf_path, all));
  }
  if (self_ && !self_->claim_.interface) self_->claim_.joints.push_back(joint);
  return j;
}

std::vector<std::string> ControllerContext::actuated_joints() const { return model_.actuated_joints(); }

}  // namespace lcm_control::cm
