// The multibody against physics we can compute by hand: a physical pendulum
// with a rotated, non-diagonal inertia (period, energy, inertia about the
// pivot), URDF link poses, every collider kind, limits on collider-less links.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "sim_server/multibody_builder.hpp"
#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "test/support/process.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

// The pendulum of data/pendulum.urdf worked out by hand from the model's numbers.
struct PendulumTheory {
  double mass, inertia_about_axis, com_distance, rest_angle, tilt;
  Eigen::Vector3d com_in_bob;

  explicit PendulumTheory(const RobotModel& m) {
    const Inertial& in = *m.link("bob")->inertial;
    const Joint& j = *m.joint("swing");
    mass = in.mass;
    com_in_bob = in.origin.translation();
    const Eigen::Matrix3d r = in.origin.linear();
    const Eigen::Vector3d axis = j.axis;  // y
    const Eigen::Vector3d perp = com_in_bob - com_in_bob.dot(axis) * axis;
    com_distance = perp.norm();
    inertia_about_axis = axis.dot(r * in.inertia * r.transpose() * axis) + mass * com_distance * com_distance;
    tilt = std::asin(j.origin.linear()(0, 2));  // rotation about y in the joint origin
    rest_angle = std::atan2(com_in_bob.x(), -com_in_bob.z()) - tilt;
  }
  double period() const { return 2 * M_PI * std::sqrt(inertia_about_axis / (mass * 9.81 * com_distance)); }
  // Height of the COM (up to a constant) at joint angle q.
  double com_height(double q) const {
    const double phi = tilt + q;
    return -std::sin(phi) * com_in_bob.x() + std::cos(phi) * com_in_bob.z();
  }
  double energy(double q, double qd) const {
    return 0.5 * inertia_about_axis * qd * qd + mass * 9.81 * com_height(q);
  }
};

TEST(sim_multibody, PendulumEffectiveInertiaIsItsInertiaAboutThePivot) {
  const RobotModel m = pendulum();
  const PendulumTheory theory(m);
  Multibody mb(m, 1e-3);
  ASSERT_EQ(mb.joints().size(), 1u);
  EXPECT_NEAR(mb.joints()[0].effective_inertia, theory.inertia_about_axis, 1e-9);
}

TEST(sim_multibody, PendulumPeriodMatchesSmallAngleTheoryWithinOnePercent) {
  const RobotModel m = pendulum();
  const PendulumTheory theory(m);
  ASSERT_NEAR(theory.rest_angle, -0.05, 1e-3);  // q = 0 starts 0.05 rad from rest
  Simulation sim(m, {});
  std::vector<double> crossings;
  double prev = sim.actuators().joint_position(0) - theory.rest_angle;
  run(sim, 10000, [&](int) { sim.actuators().set_command(0, kEff, 0.0); }, [&](int k) {
    const double x = sim.actuators().joint_position(0) - theory.rest_angle;
    if (prev < 0 && x >= 0) crossings.push_back((k + prev / (prev - x)) * 1e-3);
    prev = x;
  });
  ASSERT_GE(crossings.size(), 5u);
  const double measured = (crossings.back() - crossings.front()) / double(crossings.size() - 1);
  const double error = std::abs(measured - theory.period()) / theory.period();
  std::printf("pendulum period: measured %.6f s, theory %.6f s, error %.4f %%\n", measured, theory.period(),
              100 * error);
  EXPECT_LT(error, 0.01);
}

TEST(sim_multibody, PendulumEnergyDriftOver10sIsBelowOnePercent) {
  const RobotModel m = pendulum();
  const PendulumTheory theory(m);
  Simulation sim(m, {});
  const int link = sim.multibody().joints()[0].link;
  sim.multibody().set_state(link, theory.rest_angle + 1.0, 0.0);  // a large swing: 1 rad
  const double e0 = theory.energy(theory.rest_angle + 1.0, 0.0);
  const double swing = e0 - theory.energy(theory.rest_angle, 0.0);
  double worst = 0;
  run(sim, 10000, [&](int) { sim.actuators().set_command(0, kEff, 0.0); }, [&](int) {
    const double e = theory.energy(sim.multibody().position(link), sim.multibody().velocity(link));
    worst = std::max(worst, std::abs(e - e0) / swing);
  });
  const double final_drift =
      std::abs(theory.energy(sim.multibody().position(link), sim.multibody().velocity(link)) - e0) / swing;
  std::printf("pendulum energy over 10 s: worst deviation %.4f %%, final %.4f %% of the swing energy %.4f J\n",
              100 * worst, 100 * final_drift, swing);
  EXPECT_LT(worst, 0.01);
}

TEST(sim_multibody, UrdfDampingActsOnJointsWithoutATransmissionToo) {
  const std::string dir = lcm_control::testing::temp_dir("sim_passive");
  std::ifstream in(data("pendulum.urdf"));
  std::string urdf((std::istreambuf_iterator<char>(in)), {});
  urdf.erase(urdf.find("<transmission"), urdf.find("</transmission>") + 15 - urdf.find("<transmission"));
  urdf.replace(urdf.find("damping=\"0\""), 11, "damping=\"0.5\"");
  std::ofstream(dir + "/passive.urdf") << urdf;
  const RobotModel m = load_robot_model(dir + "/passive.urdf", "");
  ASSERT_TRUE(m.transmissions.empty());
  const PendulumTheory theory(m);
  Simulation sim(m, {});
  const int link = sim.multibody().joints()[0].link;
  sim.multibody().set_state(link, theory.rest_angle + 1.0, 0.0);
  const double swing = theory.energy(theory.rest_angle + 1.0, 0) - theory.energy(theory.rest_angle, 0);
  run(sim, 5000, {});
  // Damping ratio 0.5 / (2 sqrt(I m g d)) ~ 0.11: over 5 s (~3.4 periods) the swing energy falls below 2 %.
  const double left = theory.energy(sim.multibody().position(link), sim.multibody().velocity(link)) -
                      theory.energy(theory.rest_angle, 0);
  EXPECT_LT(left / swing, 0.02) << left / swing;
  EXPECT_GT(left / swing, 0.0);
}

TEST(sim_multibody, LinkPosesFollowTheUrdfFrames) {
  const RobotModel m = turret();
  Multibody mb(m, 1e-3);
  EXPECT_TRUE(mb.link_pose("rotor").translation().isApprox(Eigen::Vector3d(0, 0.05, 0.475), 1e-12));
  EXPECT_TRUE(mb.com_position("rotor").isApprox(Eigen::Vector3d(0.13, 0.05, 0.505), 1e-12));
  mb.set_state(mb.joints()[0].link, 0.3, 0);
  mb.set_state(mb.joints()[1].link, M_PI / 2, 0);
  // j2 turns the rotor's COM offset (0.13, 0, 0.03) onto +y.
  EXPECT_TRUE(mb.com_position("rotor").isApprox(Eigen::Vector3d(0, 0.3 + 0.05 + 0.13, 0.505), 1e-9))
      << mb.com_position("rotor").transpose();
}

TEST(sim_multibody, FixedLinkAndPrincipalFramesKeepUrdfPoses) {
  const RobotModel m = modes_bot();
  Multibody mb(m, 1e-3);
  mb.set_state(mb.joints()[mb.joint_index("j_pid")].link, 0.4, 0);
  const Eigen::Isometry3d tip = mb.link_pose("tip");
  const Eigen::Isometry3d expected = Eigen::Translation3d(0, -0.5, 0.1) * Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()) *
                                     Eigen::Translation3d(0.2, 0, 0) * Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ());
  EXPECT_TRUE(tip.isApprox(expected, 1e-9)) << tip.matrix() << "\n" << expected.matrix();
  const RobotModel p = pendulum();
  Multibody pm(p, 1e-3);
  EXPECT_TRUE(pm.link_pose("bob").translation().isApprox(Eigen::Vector3d(0.1, 0, 1.0), 1e-12));
}

TEST(sim_multibody, EveryLinkHasAColliderIncludingGeometrylessOnes) {
  const RobotModel m = modes_bot();  // box, cylinder, sphere, STL mesh; 'flap' and 'tip' have none
  Multibody mb(m, 1e-3);
  EXPECT_NE(mb.body().getBaseCollider(), nullptr);
  for (int i = 0; i < mb.body().getNumLinks(); ++i) EXPECT_NE(mb.body().getLink(i).m_collider, nullptr) << i;
  const int slide = mb.joints()[mb.joint_index("j_direct")].link;
  const btCollisionShape* s = mb.body().getLink(slide).m_collider->getCollisionShape();
  ASSERT_EQ(s->getShapeType(), COMPOUND_SHAPE_PROXYTYPE);
  EXPECT_EQ(static_cast<const btCompoundShape*>(s)->getChildShape(0)->getShapeType(), CONVEX_HULL_SHAPE_PROXYTYPE);
  btVector3 lo, hi;
  s->getAabb(btTransform::getIdentity(), lo, hi);
  EXPECT_NEAR(hi.x() - lo.x(), 0.1, 0.01);  // the 0.1 m cube of cube.stl (plus a 1 mm margin each side)
}

TEST(sim_multibody, NoHiddenDampingSleepOrDefaultVelocityClamp) {
  const RobotModel m = turret();
  Multibody mb(m, 1e-3);
  EXPECT_EQ(mb.body().getLinearDamping(), 0);
  EXPECT_EQ(mb.body().getAngularDamping(), 0);
  EXPECT_FALSE(mb.body().getCanSleep());
  // Not Bullet's 100 (a fast wheel), nor a URDF velocity limit (a clamp inside the step hides torques from the
  // implicit rows): 1e4, a safety net; each joint's limit is applied after the step.
  EXPECT_EQ(mb.body().getMaxCoordinateVelocity(), 1e4);
}

TEST(sim_multibody, UnreadableMeshIsAModelError) {
  const std::string dir = lcm_control::testing::temp_dir("sim_mesh");
  std::ifstream in(data("modes_bot.urdf"));
  std::string urdf((std::istreambuf_iterator<char>(in)), {});
  urdf.replace(urdf.find("cube.stl"), 8, "broken.stl");
  std::ofstream(dir + "/broken.urdf") << urdf;
  std::ofstream(dir + "/broken.stl") << "solid nothing\nendsolid nothing\n";
  const RobotModel m = load_robot_model(dir + "/broken.urdf", "");
  try {
    Multibody mb(m, 1e-3);
    FAIL() << "expected a ModelError";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("broken.stl"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lcm_control::sim
