// cmctl's tables: a controller of many joints keeps `cmctl list` narrow (the whole list with --verbose).
#include <gtest/gtest.h>

#include <algorithm>

#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/cm_views.hpp"

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

// A controller that writes another's reference interfaces (ROS 2 chaining) is shown as a link of the chain, in text
// and in Graphviz.
TEST(CmctlChains, AControllerWritingReferenceInterfacesIsALinkOfTheChain) {
  cm_response_t list{};
  list.controllers = {controller("pid_left", {"left_wheel"}), controller("base", {"pid_left/left_wheel"})};
  for (auto& c : list.controllers) c.hardware_interface = "VelocityJointInterface";
  list.num_controllers = 2;
  const std::string text = controller_chains_text(list);
  EXPECT_NE(text.find("base (joint_trajectory_controller/JointTrajectoryController, running)\n  writes "
                      "pid_left/left_wheel/velocity -> pid_left (its reference interface)"),
            std::string::npos)
      << text;
  EXPECT_EQ(text.find("no chained controllers"), std::string::npos) << text;
  EXPECT_NE(controller_chains_dot(list).find("\"base\" -> \"pid_left\" [label=\"pid_left/left_wheel/velocity\"]"),
            std::string::npos)
      << controller_chains_dot(list);
  list.controllers.pop_back();
  list.num_controllers = 1;
  EXPECT_NE(controller_chains_text(list).find("no chained controllers"), std::string::npos);
}

}  // namespace
}  // namespace lcm_control::tools
