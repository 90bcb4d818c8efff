#include "controller_manager/claims.hpp"

#include <gtest/gtest.h>

#include "test/controller_manager/rig.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::data;

namespace {
RobotModel model() { return load_robot_model(data("test_bot.urdf"), data("test_bot.yaml")); }
}  // namespace

TEST(ControllerManagerClaims, InterfaceOfferedByTheTransmissionIsAccepted) {
  const RobotModel m = model();
  EXPECT_EQ(check_interface(m, "c", "slide", Interface::Position), "");
  EXPECT_EQ(check_interface(m, "c", "wheel", Interface::Velocity), "");
  EXPECT_EQ(check_interface(m, "c", "arm", Interface::Effort), "");
}

TEST(ControllerManagerClaims, InterfaceMismatchNamesControllerJointNeededAndOffered) {
  const std::string why = check_interface(model(), "wrong_interface", "slide", Interface::Velocity);
  EXPECT_NE(why.find("'wrong_interface'"), std::string::npos) << why;
  EXPECT_NE(why.find("joint 'slide'"), std::string::npos) << why;
  EXPECT_NE(why.find("needs VelocityJointInterface"), std::string::npos) << why;
  EXPECT_NE(why.find("offers only PositionJointInterface"), std::string::npos) << why;
}

TEST(ControllerManagerClaims, UnknownJointListsTheMovingJoints) {
  const std::string why = check_interface(model(), "c", "elbow", Interface::Position);
  EXPECT_NE(why.find("joint 'elbow' is not in the URDF"), std::string::npos) << why;
  EXPECT_NE(why.find("slide, tilt, wheel, roll, arm, spin"), std::string::npos) << why;
}

TEST(ControllerManagerClaims, TwoControllersOnOneJointConflictWhateverTheInterface) {
  Claim a{Interface::Position, {"slide", "tilt"}}, b{Interface::Velocity, {"wheel", "tilt"}};
  const auto c = find_conflict({{"a", &a}, {"b", &b}});
  ASSERT_TRUE(c);
  EXPECT_EQ(c->message(), "controllers 'a' and 'b' would both claim joint 'tilt'");
}

TEST(ControllerManagerClaims, StateReadersNeverConflict) {
  Claim reader{std::nullopt, {"slide", "tilt"}}, reader2{std::nullopt, {"slide"}}, cmd{Interface::Position, {"slide"}};
  EXPECT_FALSE(find_conflict({{"jsc", &reader}, {"jsc2", &reader2}, {"c", &cmd}}));
}
