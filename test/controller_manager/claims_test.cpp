#include "controller_interface/claims.hpp"
#include "controller_manager/hardware.hpp"

#include <gtest/gtest.h>

#include "test/controller_manager/rig.hpp"
#include "description/load.hpp"

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
  Claim a{Interface::Position, {"slide", "tilt"}, {}, {}}, b{Interface::Velocity, {"wheel", "tilt"}, {}, {}};
  const auto c = find_conflict({{"a", &a}, {"b", &b}});
  ASSERT_TRUE(c);
  EXPECT_EQ(c->message(), "controllers 'a' and 'b' would both claim joint 'tilt'");
}

TEST(ControllerManagerClaims, StateReadersNeverConflict) {
  Claim reader{std::nullopt, {"slide", "tilt"}, {}, {}}, reader2{std::nullopt, {"slide"}, {}, {}}, cmd{Interface::Position, {"slide"}, {}, {}};
  EXPECT_FALSE(find_conflict({{"jsc", &reader}, {"jsc2", &reader2}, {"c", &cmd}}));
}

namespace {
RobotModel switch_arm() {
  return load_robot_model(std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/switch_arm.urdf",
                          std::string(LCM_CONTROL_SOURCE_DIR) + "/test/robots/switch_arm.yaml");
}

hardware_state_t state_in_modes(int8_t j1, int8_t j2) {
  hardware_state_t s{};
  s.session = 7;
  s.num_actuators = 2;
  s.name = {"j1_actuator", "j2_actuator"};
  s.mode = {j1, j2};
  s.position = s.velocity = s.effort = {0.0, 0.0};
  return s;
}
}  // namespace

TEST(ControllerManagerClaims, Ros2ControlJointAcceptsEveryCommandInterfaceItOffers) {
  const RobotModel m = switch_arm();
  EXPECT_EQ(check_interface(m, "p", "j1", Interface::Position), "");
  EXPECT_EQ(check_interface(m, "v", "j1", Interface::Velocity), "");
  const std::string why = check_interface(m, "e", "j1", Interface::Effort);
  EXPECT_NE(why.find("controller 'e' needs EffortJointInterface on joint 'j1', but transmission 'SwitchArm/j1' offers "
                     "only PositionJointInterface, VelocityJointInterface"),
            std::string::npos)
      << why;
}

TEST(ControllerManagerClaims, Ros1TransmissionStillTakesOnlyItsFirstInterface) {
  RobotModel m = switch_arm();
  for (TransmissionSpec& t : m.transmissions) t.any_interface = false;
  const std::string why = check_interface(m, "v", "j1", Interface::Velocity);
  EXPECT_NE(why.find("offers PositionJointInterface, VelocityJointInterface but the hardware takes only the first"),
            std::string::npos)
      << why;
}

TEST(ControllerManagerHardware, BindsHardwareThatIsInAnyOfferedModeOfARos2ControlJoint) {
  RobotModel m = switch_arm();
  hardware_command_t cmd;
  {
    Hardware hw(m);
    EXPECT_EQ(hw.bind(state_in_modes(hardware_command_t::MODE_VELOCITY, hardware_command_t::MODE_POSITION), cmd), "");
    EXPECT_NE(hw.bind(state_in_modes(hardware_command_t::MODE_EFFORT, hardware_command_t::MODE_POSITION), cmd), "");
  }
  for (TransmissionSpec& t : m.transmissions) t.any_interface = false;
  Hardware ros1(m);
  EXPECT_EQ(ros1.bind(state_in_modes(hardware_command_t::MODE_VELOCITY, hardware_command_t::MODE_POSITION), cmd),
            "hardware does not match the URDF: actuator 'j1_actuator' takes velocity commands but the URDF says joint "
            "'j1' takes PositionJointInterface");
}
