// cmctl's tables: a controller of many joints keeps `cmctl list` narrow (the whole list with --verbose).
#include <gtest/gtest.h>

#include <algorithm>

#include "tools/lib/cm_client.hpp"

namespace lcm_control::tools {
namespace {

controller_info_t controller(const std::string& name, std::vector<std::string> joints) {
  controller_info_t c{};
  c.name = name;
  c.type = "joint_trajectory_controller/JointTrajectoryController";
  c.state = "running";
  c.num_joints = int32_t(joints.size());
  c.joints = std::move(joints);
  c.hardware_interface = "position";
  return c;
}

TEST(CmctlList, MoreThanThreeJointsAreShownAsFirstLastAndCount) {
  const std::vector<controller_info_t> list = {
      controller("scaled_joint_trajectory_controller",
                 {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint", "wrist_2_joint",
                  "wrist_3_joint"}),
      controller("gripper", {"finger_joint"})};
  const std::string narrow = controller_table(list);
  EXPECT_NE(narrow.find("shoulder_pan_joint..wrist_3_joint (6)"), std::string::npos) << narrow;
  EXPECT_NE(narrow.find("  finger_joint  "), std::string::npos) << narrow;
  size_t widest = 0;
  for (size_t at = 0, next; at < narrow.size(); at = next + 1) {
    next = narrow.find('\n', at);
    widest = std::max(widest, next - at);
  }
  EXPECT_LE(widest, 150u) << narrow;
  const std::string all = controller_table(list, false, true);
  EXPECT_NE(all.find("shoulder_pan_joint,shoulder_lift_joint,elbow_joint,wrist_1_joint,wrist_2_joint,wrist_3_joint"),
            std::string::npos)
      << all;
}

}  // namespace
}  // namespace lcm_control::tools
