// Forward kinematics (robot_state_publisher's, for state-publisher): the pose of
// every URDF link in the world (the root link's frame) from joint positions.
#pragma once

#include <Eigen/Geometry>
#include <map>
#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

struct LinkPose {
  std::string link;
  Eigen::Isometry3d pose;  // link frame in the world
};

// The motion a joint adds at position q: rotation about the axis for revolute and
// continuous joints, translation along it for prismatic ones, none otherwise.
Eigen::Isometry3d joint_motion(const Joint& joint, double q);

// Every link in URDF order: world pose = parent pose * joint origin * motion.
// Joints missing from `positions` are taken at 0.
std::vector<LinkPose> forward_kinematics(const RobotModel& model, const std::map<std::string, double>& positions);

}  // namespace lcm_control
