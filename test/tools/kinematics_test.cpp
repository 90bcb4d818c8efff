// Forward kinematics against hand-computed poses: turret_bot at three joint
// configurations, and a chain with offsets that checks the composition order.
#include "description/kinematics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "test/support/process.hpp"
#include "description/urdf_reader.hpp"
#include "description/load.hpp"

using namespace lcm_control;

namespace {
Eigen::Isometry3d pose_of(const std::vector<LinkPose>& poses, const std::string& link) {
  for (const auto& p : poses)
    if (p.link == link) return p.pose;
  ADD_FAILURE() << "no link " << link;
  return Eigen::Isometry3d::Identity();
}
void expect_pose(const Eigen::Isometry3d& got, const Eigen::Vector3d& xyz, double yaw, const std::string& what) {
  EXPECT_TRUE(got.translation().isApprox(xyz, 1e-12) || (got.translation() - xyz).norm() < 1e-12)
      << what << ": " << got.translation().transpose() << " vs " << xyz.transpose();
  const Eigen::Matrix3d r = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_LT((got.linear() - r).norm(), 1e-12) << what;
}
}  // namespace

// turret_bot: j1 slides the slider along y from the base; j2 turns the rotor
// about z at (0, 0.05, 0.475) in the slider frame. By hand:
//   slider = (0, q1, 0), no rotation; rotor = (0, q1 + 0.05, 0.475), yaw q2.
TEST(Kinematics, TurretBotAtThreeConfigurations) {
  const RobotModel model = load_robot_model(lcm_control::testing::source("config/turret_bot.urdf"), "");
  const double configs[3][2] = {{0.0, 0.0}, {0.5, 1.0}, {1.0, -2.5}};
  for (const auto& q : configs) {
    const auto poses = forward_kinematics(model, {{"j1", q[0]}, {"j2", q[1]}});
    ASSERT_EQ(poses.size(), 3u);
    EXPECT_EQ(poses[0].link, "base");
    const std::string at = "q = (" + std::to_string(q[0]) + ", " + std::to_string(q[1]) + ")";
    expect_pose(pose_of(poses, "base"), {0, 0, 0}, 0, "base " + at);
    expect_pose(pose_of(poses, "slider"), {0, q[0], 0}, 0, "slider " + at);
    expect_pose(pose_of(poses, "rotor"), {0, q[0] + 0.05, 0.475}, q[1], "rotor " + at);
    // A point on the rotor 0.13 m along its x axis sweeps a circle about the joint.
    const Eigen::Vector3d tip = pose_of(poses, "rotor") * Eigen::Vector3d(0.13, 0, 0);
    EXPECT_NEAR(tip.x(), 0.13 * std::cos(q[1]), 1e-12);
    EXPECT_NEAR(tip.y(), q[0] + 0.05 + 0.13 * std::sin(q[1]), 1e-12);
  }
}

TEST(Kinematics, OriginThenMotionAlongTheChain) {
  const std::string dir = lcm_control::testing::temp_dir("fk");
  const std::string urdf = dir + "/chain.urdf";
  std::ofstream(urdf) << R"(<?xml version="1.0"?>
<robot name="chain">
  <link name="a"/>
  <joint name="ja" type="continuous">
    <parent link="a"/><child link="b"/>
    <origin xyz="1 0 0" rpy="0 0 1.5707963267948966"/>
    <axis xyz="0 0 1"/>
  </joint>
  <link name="b"/>
  <joint name="jb" type="prismatic">
    <parent link="b"/><child link="c"/>
    <origin xyz="1 0 0" rpy="0 0 0"/>
    <axis xyz="2 0 0"/>
    <limit lower="0" upper="1" effort="1" velocity="1"/>
  </joint>
  <link name="c"/>
  <joint name="jc" type="fixed">
    <parent link="c"/><child link="d"/>
    <origin xyz="0 0 0.5" rpy="0 0 0"/>
  </joint>
  <link name="d"/>
</robot>)";
  RobotModel model;
  load_urdf_into(model, urdf, {});
  // b: at (1,0,0), yaw 90 deg + q; c: b * (1,0,0) * slide along b's x by s.
  const double q = 0.5, s = 0.25;
  const auto poses = forward_kinematics(model, {{"ja", q}, {"jb", s}});
  const double yaw = M_PI / 2 + q;
  expect_pose(pose_of(poses, "b"), {1, 0, 0}, yaw, "b");
  const Eigen::Vector3d c(1 + (1 + s) * std::cos(yaw), (1 + s) * std::sin(yaw), 0);
  expect_pose(pose_of(poses, "c"), c, yaw, "c");
  expect_pose(pose_of(poses, "d"), c + Eigen::Vector3d(0, 0, 0.5), yaw, "d");
  // A joint not given is at 0.
  const auto zero = forward_kinematics(model, {});
  expect_pose(pose_of(zero, "d"), {1, 1, 0.5}, M_PI / 2, "d at zero");
}
