// <gazebo reference="LINK"> tags: <turnGravityOff> makes that link weightless (as in Gazebo), and every tag the
// simulator does not read is named in one warning instead of being dropped silently.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using ::testing::HasSubstr;
using testing::data;

TEST(sim_gazebo_tags, ALinkWithTurnGravityOffFeelsNoGravity) {
  const RobotModel model = load_robot_model(data("gravity_off.urdf"), "");
  ASSERT_TRUE(model.link("floating_arm")->gravity_off);
  ASSERT_FALSE(model.link("falling_arm")->gravity_off);
  Simulation sim(model, {}, {}, {});
  testing::run(sim, 300, {});
  Multibody& mb = sim.multibody();
  const double floating = mb.position(mb.joints()[mb.joint_index("floating_joint")].link);
  const double falling = mb.position(mb.joints()[mb.joint_index("falling_joint")].link);
  std::printf("after 0.3 s: floating_joint %.3g rad, falling_joint %.3g rad\n", floating, falling);
  EXPECT_NEAR(floating, 0.0, 1e-9);  // horizontal, weightless: stays
  EXPECT_GT(falling, 0.5);           // swings down (+y axis: +q turns +x towards -z)
}

TEST(sim_gazebo_tags, TagsNotSimulatedAreNamedInOneWarning) {
  const RobotModel model = load_robot_model(data("gravity_off.urdf"), "");
  int naming = 0;
  for (const auto& w : model.warnings)
    if (w.find("Gazebo tags not simulated") != std::string::npos) {
      ++naming;
      EXPECT_THAT(w, HasSubstr("gravity_off.urdf"));
      EXPECT_THAT(w, HasSubstr("ignored: <gazebo reference> material (read are"));  // and only that one
    }
  EXPECT_EQ(naming, 1);
}

}  // namespace
}  // namespace lcm_control::sim
