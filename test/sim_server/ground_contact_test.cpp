// What a mobile robot from a ROS package needs of the simulation: Collada meshes in the frame the URDF means (a Z_UP
// and a Y_UP file of the same shape give the same collision box; <unit meter> scales it), a free base by default
// when the URDF has no joint to `world`, passive joints on Gazebo springs settling where k x = m g, and directional
// friction (<fdir1>, <mu2>) that holds along one axis and slides across it.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/collision_shapes.hpp"
#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using ::testing::HasSubstr;
using testing::data;

std::string mesh(const std::string& file) { return std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/mobile/meshes/" + file; }

// The collision box of a link made of one mesh.
void mesh_box(const std::string& path, btVector3& lo, btVector3& hi) {
  Link l;
  l.name = "shell";
  Geometry g;
  g.type = Geometry::Type::Mesh;
  g.mesh_uri = g.mesh_path = path;
  l.collisions.push_back(g);
  ShapeStore store;
  btCollisionShape* s = make_link_shape(l, Eigen::Isometry3d::Identity(), store, "robot.urdf");
  ASSERT_NE(s, nullptr);
  btTransform identity;
  identity.setIdentity();
  s->getAabb(identity, lo, hi);
}

TEST(sim_ground_contact, ZUpAndYUpColladaOfOneShapeGiveTheSameBoxInTheUrdfFrame) {
  btVector3 zlo, zhi, ylo, yhi, mlo, mhi;
  ASSERT_NO_FATAL_FAILURE(mesh_box(mesh("block_z_up.dae"), zlo, zhi));
  ASSERT_NO_FATAL_FAILURE(mesh_box(mesh("block_y_up.dae"), ylo, yhi));
  ASSERT_NO_FATAL_FAILURE(mesh_box(mesh("block_mm.dae"), mlo, mhi));  // in mm, <unit meter="0.001">
  std::printf("Z_UP box (%.4f %.4f %.4f)..(%.4f %.4f %.4f), Y_UP (%.4f %.4f %.4f)..(%.4f %.4f %.4f)\n", zlo.x(),
              zlo.y(), zlo.z(), zhi.x(), zhi.y(), zhi.z(), ylo.x(), ylo.y(), ylo.z(), yhi.x(), yhi.y(), yhi.z());
  // The vertices as written (x 0.05..0.45, y -0.1..0.1, z 0..0.06), whatever the label, within the hull's margins.
  const btVector3 want_lo(0.05, -0.1, 0.0), want_hi(0.45, 0.1, 0.06);
  for (const auto& [lo, hi] : {std::pair{zlo, zhi}, std::pair{ylo, yhi}, std::pair{mlo, mhi}})
    for (int a = 0; a < 3; ++a) {
      EXPECT_NEAR(lo[a], want_lo[a], 0.0025) << "axis " << a;
      EXPECT_NEAR(hi[a], want_hi[a], 0.0025) << "axis " << a;
    }
}

TEST(sim_ground_contact, AMeshThatDoesNotParseIsRefusedNamingTheFile) {
  const std::string bad = ::testing::TempDir() + "/broken.dae";
  FILE* f = std::fopen(bad.c_str(), "w");
  std::fputs("<COLLADA><library_geometries><geometry", f);
  std::fclose(f);
  btVector3 lo, hi;
  try {
    mesh_box(bad, lo, hi);
    ADD_FAILURE() << "a broken mesh was accepted";
  } catch (const ModelError& e) {
    EXPECT_THAT(e.what(), HasSubstr("robot.urdf: link 'shell': cannot read collision mesh"));
    EXPECT_THAT(e.what(), HasSubstr(bad));
  }
}

TEST(sim_ground_contact, ABaseWithNoJointToWorldIsFreeByDefaultAndWeldedOnRequest) {
  const RobotModel table = load_robot_model(data("sprung_table.urdf"), "");
  const RobotModel arm = load_robot_model(data("ft_pendulum.urdf"), "");
  ASSERT_EQ(arm.root_link, "world");
  EXPECT_TRUE(floating_base_for(table, BaseMount::Auto));
  EXPECT_FALSE(floating_base_for(arm, BaseMount::Auto));
  EXPECT_FALSE(floating_base_for(table, BaseMount::Fixed));
  EXPECT_TRUE(floating_base_for(arm, BaseMount::Floating));
}

TEST(sim_ground_contact, PassiveSprungLegsSettleWhereTheSpringCarriesTheWeight) {
  const RobotModel model = load_robot_model(data("sprung_table.urdf"), "");
  ASSERT_TRUE(model.joint("leg_0")->spring);
  EXPECT_EQ(model.joint("leg_0")->spring->stiffness, 2000);
  bool noted = false;
  for (const auto& n : model.notes)
    noted = noted || n.find("joint 'leg_0' is passive (nothing drives it): it moves freely on its spring") !=
                         std::string::npos;
  EXPECT_TRUE(noted);
  Simulation sim(model, {}, {}, WorldOptions{true, true});
  testing::run(sim, 3000, {});  // 3 s
  Multibody& mb = sim.multibody();
  const double want = 8 * 9.81 / 4 / 2000;  // k x = m g: a quarter of the table on each spring
  for (int i = 0; i < 4; ++i) {
    const double q = mb.position(mb.joints()[mb.joint_index("leg_" + std::to_string(i))].link);
    std::printf("leg_%d settled at %.5f m (k x = m g: %.5f m)\n", i, q, want);
    EXPECT_NEAR(q, want, 0.05 * want);
  }
  EXPECT_NEAR(mb.base_linear_velocity().norm(), 0, 1e-4) << "at rest";
}

TEST(sim_ground_contact, DirectionalFrictionHoldsAlongFdir1AndSlidesAcrossIt) {
  const RobotModel model = load_robot_model(data("directional_block.urdf"), "");
  ASSERT_TRUE(model.link("block")->friction_direction);
  // Pushed with 20 N (a fifth of mu m g) along its x axis, then across it, each from rest: the block yawed 90 degrees
  // carries fdir1 with it.
  for (const double yaw : {0.0, M_PI / 2}) {
    for (const int axis : {0, 1}) {
      WorldOptions w{true, true};
      w.base_yaw = yaw;
      Simulation sim(model, {}, {}, w);
      testing::run(sim, 200, {});  // settle
      Multibody& mb = sim.multibody();
      const Eigen::Vector3d start = mb.base_pose().translation();
      const Eigen::Vector3d push = mb.base_pose().linear() * (axis == 0 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()) * 20;
      testing::run(sim, 1000, [&](int) { mb.body().addBaseForce(btVector3(push.x(), push.y(), push.z())); });
      const double moved = (mb.base_pose().translation() - start).norm();
      std::printf("yaw %.2f, pushed along its %s axis: moved %.4f m in 1 s\n", yaw, axis == 0 ? "x" : "y", moved);
      if (axis == 0)
        EXPECT_LT(moved, 1e-3) << "friction 1 along fdir1 holds 20 N";
      else
        EXPECT_NEAR(moved, 0.5 * 2.0 * 1.0, 0.05) << "no friction across it: 20 N on 10 kg, 2 m/s^2 for 1 s";
    }
  }
}

}  // namespace
}  // namespace lcm_control::sim
