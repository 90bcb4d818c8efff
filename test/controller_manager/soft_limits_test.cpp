// The URDF's soft limits applied by the controller manager's hardware layer to every command, for the interface
// the controller claimed (position, velocity, effort), as joint_limits_interface's soft-limit handles do.
#include <gtest/gtest.h>

#include <fstream>

#include "lcm_control/float64_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/tools/tool_test_util.hpp"
#include "controllers/builtin.hpp"

namespace lcm_control::testing {
namespace {

// test_bot with <safety_controller> on tilt (position), roll (velocity) and arm (effort): soft [-1, 1].
struct SoftRig {
  SoftRig() {
    const std::string dir = temp_dir("soft_limits");
    std::string urdf = read_text(data("test_bot.urdf"));
    for (const std::string joint : {"tilt", "roll", "arm"}) {
      const auto at = urdf.find("</joint>", urdf.find("<joint name=\"" + joint + "\""));
      urdf.insert(at, "  <safety_controller soft_lower_limit=\"-1\" soft_upper_limit=\"1\" k_position=\"20\" "
                      "k_velocity=\"50\"/>\n  ");
    }
    std::ofstream(dir + "/soft.urdf") << urdf;
    std::ofstream(dir + "/soft.yaml") << read_text(data("test_bot.yaml"))
                                      << "roll_velocity:\n  type: velocity_controllers/JointVelocityController\n"
                                         "  joint: roll\n";
    rig = std::make_unique<Rig>(cm::builtin_registry(), dir + "/soft.urdf", dir + "/soft.yaml");
  }
  void command(const std::string& controller, double value) {
    float64_t m{};
    m.data = value;
    rig->publish(controller + "/command", m);
  }
  std::unique_ptr<Rig> rig;
};

TEST(SoftLimitsInTheLoop, ModelReadsTheSafetyController) {
  SoftRig s;
  const Joint* tilt = s.rig->model.joint("tilt");
  ASSERT_TRUE(tilt && tilt->soft);
  EXPECT_EQ(tilt->soft->upper, 1);
  EXPECT_EQ(tilt->soft->k_velocity, 50);
  EXPECT_FALSE(s.rig->model.joint("slide")->soft);
}

TEST(SoftLimitsInTheLoop, PositionCommandsStopAtTheSoftLimitRateLimitedOnTheWay) {
  SoftRig s;
  s.rig->start("tilt_position");
  s.command("tilt_position", 2.5);  // beyond the soft limit, inside the hard one (3)
  double prev = s.rig->joint("tilt").position, most = -1e9;
  for (int k = 0; k < 3000; ++k) {
    s.rig->cycle();
    const double cmd = s.rig->joint("tilt").command;
    EXPECT_LE(cmd - prev, 5 * 0.001 + 1e-12) << "step " << k << ": faster than the velocity limit";
    most = std::max(most, cmd);
    prev = cmd;
  }
  EXPECT_LE(most, 1.0);
  EXPECT_NEAR(prev, 1.0, 1e-6);
  EXPECT_NEAR(s.rig->joint("tilt").position, 1.0, 0.01);
}

TEST(SoftLimitsInTheLoop, VelocityAndEffortCommandsFollowTheFormulasAndHoldTheJointNearTheSoftLimit) {
  SoftRig s;
  s.rig->start("roll_velocity");
  s.rig->start("arm_effort");
  s.command("roll_velocity", 8.0);
  s.command("arm_effort", 40.0);
  const JointLimits roll = s.rig->model.joint("roll")->limits(), arm = s.rig->model.joint("arm")->limits();
  const SoftLimits soft = *s.rig->model.joint("roll")->soft;
  double roll_max = -1e9, arm_max = -1e9;
  for (int k = 0; k < 3000; ++k) {
    s.rig->cycle();
    const cm::JointData& r = s.rig->joint("roll");
    const cm::JointData& a = s.rig->joint("arm");
    ASSERT_DOUBLE_EQ(r.command, velocity_soft_limits(roll, soft, 8.0, r.position)) << "step " << k;
    ASSERT_DOUBLE_EQ(a.command, effort_soft_limits(arm, soft, 40.0, a.position, a.velocity)) << "step " << k;
    roll_max = std::max(roll_max, r.position);
    arm_max = std::max(arm_max, a.position);
  }
  // Without soft limits both would run to their hard limit (3 rad); here they settle at the soft one.
  EXPECT_LT(roll_max, 1.05);
  EXPECT_NEAR(s.rig->joint("roll").position, 1.0, 0.01);
  EXPECT_LT(arm_max, 1.3);
  EXPECT_GT(s.rig->joint("arm").position, 0.8);
}

}  // namespace
}  // namespace lcm_control::testing
