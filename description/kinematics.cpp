#include "description/kinematics.hpp"

#include <functional>

namespace lcm_control {

Eigen::Isometry3d joint_motion(const Joint& joint, double q) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d axis = joint.axis.norm() > 0 ? joint.axis.normalized() : Eigen::Vector3d::UnitX();
  switch (joint.type) {
    case JointType::Revolute:
    case JointType::Continuous: m.linear() = Eigen::AngleAxisd(q, axis).toRotationMatrix(); break;
    case JointType::Prismatic: m.translation() = axis * q; break;
    default: break;
  }
  return m;
}

std::vector<LinkPose> forward_kinematics(const RobotModel& model, const std::map<std::string, double>& positions) {
  std::map<std::string, Eigen::Isometry3d> done;
  std::function<Eigen::Isometry3d(const std::string&, int)> pose_of = [&](const std::string& link, int depth) {
    const auto it = done.find(link);
    if (it != done.end()) return it->second;
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    const Link* l = model.link(link);
    const Joint* j = l && !l->parent_joint.empty() ? model.joint(l->parent_joint) : nullptr;
    if (j && depth < 10000) {
      const auto q = positions.find(j->name);
      pose = pose_of(j->parent_link, depth + 1) * j->origin * joint_motion(*j, q == positions.end() ? 0.0 : q->second);
    }
    done.emplace(link, pose);
    return pose;
  };
  std::vector<LinkPose> out;
  out.reserve(model.links.size());
  for (const auto& l : model.links) out.push_back(LinkPose{l.name, pose_of(l.name, 0)});
  return out;
}

}  // namespace lcm_control
