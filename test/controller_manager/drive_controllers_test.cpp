// ros2_controllers' drives (controllers/steering_controllers.cpp, tricycle_controller.cpp, holonomic_drives.cpp) on
// drive_bot.urdf, mock hardware played by the rig at 1 kHz: the inverse kinematics each writes for a twist, the
// odometry it integrates back from the joints, its timeout, both generations of parameter names, and its refusals
// of bad parameters naming the key and the joint.
#include <gtest/gtest.h>

#include <cmath>

#include "lcm_control/ackermann_drive_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "test/support/lcm_test.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"

using namespace lcm_control;
using lcm_control::testing::data;
using lcm_control::testing::Recorder;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

struct DriveRig : lcm_control::testing::Rig {
  DriveRig() : Rig(cm::builtin_registry(), data("drive_bot.urdf"), data("drive_bot.yaml")) {}
  double velocity(const std::string& j) { return joint(j).velocity; }
  double position(const std::string& j) { return joint(j).position; }
  void twist(const std::string& channel, double vx, double vy, double wz) {
    twist_t t{};
    t.linear.x = vx;
    t.linear.y = vy;
    t.angular.z = wz;
    publish(channel, t);
  }
};

// drive_bot's parameter file with one controller's section replaced by `section` (YAML text, its type kept); the
// message of loading it.
std::string load_with(const std::string& name, const std::string& section) {
  RobotModel m = load_robot_model(data("drive_bot.urdf"), data("drive_bot.yaml"));
  for (auto& c : m.controllers)
    if (c.name == name) {
      const std::string type = c.type;
      c.params = YAML::Load(section);
      c.params["type"] = type;
    }
  Bus bus("memq://", "");
  cm::ControllerManager manager(m, bus, cm::builtin_registry());
  const cm::Reply r = manager.load(name);
  EXPECT_FALSE(r.ok) << section;
  return r.message;
}

TEST(DriveControllers, AckermannSteersEachWheelToItsOwnAngleAndDrivesEachAtItsOwnRadius) {
  DriveRig rig;
  Recorder<odometry_t> odom(rig.bus.lcm(), "ackermann/odometry");
  rig.start("ackermann");
  const double v = 0.5, w = 0.25, L = 0.5, T = 0.4, r = 0.1;  // a 2 m radius
  for (int k = 0; k < 100; ++k) {  // a fresh reference each 0.1 s (reference_timeout 0.2)
    rig.twist("ackermann/reference", v, 0, w);
    rig.cycle(100);
  }
  const double phi = std::atan(w * L / v);
  const double right = std::atan2(2 * L * std::sin(phi), 2 * L * std::cos(phi) + T * std::sin(phi));
  const double left = std::atan2(2 * L * std::sin(phi), 2 * L * std::cos(phi) - T * std::sin(phi));
  EXPECT_NEAR(rig.position("steer_right"), right, 1e-9);
  EXPECT_NEAR(rig.position("steer_left"), left, 1e-9);
  EXPECT_NEAR(std::tan(left), L / (2.0 - T / 2), 1e-9) << "the inner wheel on the 1.8 m circle";
  EXPECT_NEAR(std::tan(right), L / (2.0 + T / 2), 1e-9) << "the outer wheel on the 2.2 m circle";
  EXPECT_NEAR(rig.velocity("traction_right"), v / r * (2.0 + T / 2) / 2.0, 1e-6);
  EXPECT_NEAR(rig.velocity("traction_left"), v / r * (2.0 - T / 2) / 2.0, 1e-6);
  // The odometry from the two steering angles and the two wheels: 10 s on the 2 m circle (less the first cycles).
  ASSERT_FALSE(odom.messages.empty());
  const odometry_t& o = odom.messages.back();
  EXPECT_NEAR(o.linear.x, v, 1e-6);
  EXPECT_NEAR(o.angular.z, w, 1e-6);
  EXPECT_NEAR(o.yaw, std::remainder(w * 10, 2 * M_PI), 0.01);
  EXPECT_NEAR(std::hypot(o.position.x, o.position.y - 2.0), 2.0, 0.01) << "on the circle about (0, 2)";
  EXPECT_EQ(odom.messages.size(), 10000u) << "every update, as ROS 2 publishes it";

  // reference_timeout: 0.2 s after the last twist the traction stops, the steering stays.
  rig.cycle(250);
  EXPECT_NEAR(rig.velocity("traction_right"), 0, 1e-12);
  EXPECT_NEAR(rig.position("steer_right"), right, 1e-9);
}

TEST(DriveControllers, BicycleReadsHumblesFrontSteeringNamesAndTricycleSteeringSplitsItsAxle) {
  DriveRig rig;
  rig.start("bicycle");
  rig.twist("bicycle/reference", 1.0, 0, 0.1);
  rig.cycle(50);
  // ros2_control_demos' car-like example: steering atan(0.1 * L / 1.0), traction 1.0 / r.
  EXPECT_NEAR(rig.position("steer"), std::atan(0.1 * 0.5 / 1.0), 1e-9);
  EXPECT_NEAR(rig.velocity("traction"), 10.0, 1e-9);

  DriveRig tri;
  tri.start("tricycle_steering");
  for (int k = 0; k < 5; ++k) {
    tri.twist("tricycle_steering/reference", 0.5, 0, 0.25);
    tri.cycle(100);
  }
  const double R = 0.5 / std::tan(tri.position("steer"));
  EXPECT_NEAR(R, 2.0, 1e-6);
  EXPECT_NEAR(tri.velocity("traction_right"), 5.0 * (R + 0.2) / R, 1e-6);
  EXPECT_NEAR(tri.velocity("traction_left"), 5.0 * (R - 0.2) / R, 1e-6);
}

TEST(DriveControllers, TricycleTurnsOnTheSpotWithItsWheelAcrossAndPublishesItsAckermannCommand) {
  DriveRig rig;
  rig.cycle();
  RobotModel m = rig.model;
  for (auto& c : m.controllers)
    if (c.name == "tricycle") c.params["publish_ackermann_command"] = true;
  rig.cm = std::make_unique<cm::ControllerManager>(m, rig.bus, cm::builtin_registry());
  Recorder<ackermann_drive_t> ackermann(rig.bus.lcm(), "tricycle/cmd_ackermann");
  rig.start("tricycle");
  rig.twist("tricycle/cmd_vel", 0.0, 0, 0.5);
  rig.cycle(150);  // under cmd_vel_timeout 200 ms
  EXPECT_NEAR(rig.position("steer"), M_PI_2, 1e-9);
  EXPECT_NEAR(rig.velocity("traction"), 0.5 * 0.5 / 0.1, 1e-9) << "|w| * wheelbase / wheel_radius";
  ASSERT_FALSE(ackermann.messages.empty());
  EXPECT_NEAR(ackermann.messages.back().steering_angle, M_PI_2, 1e-9);
  EXPECT_NEAR(ackermann.messages.back().speed, 2.5, 1e-9) << "the wheel's rad/s, as ROS 2 sends it";
  // Forward at v: straight ahead, v / r, the speed held back (x cos 90 degrees) while the wheel still stands across.
  rig.twist("tricycle/cmd_vel", 0.4, 0, 0);
  rig.cycle(1);
  EXPECT_LT(std::abs(rig.joint("traction").command), 1e-9);
  rig.cycle(20);
  EXPECT_NEAR(rig.position("steer"), 0, 1e-9);
  EXPECT_NEAR(rig.velocity("traction"), 4.0, 1e-9);
  rig.cycle(200);  // past cmd_vel_timeout: the wheel stops
  EXPECT_NEAR(rig.velocity("traction"), 0, 1e-12);
}

TEST(DriveControllers, MecanumWheelsForEachAxisAndOdometryBackFromTheirSpeeds) {
  DriveRig rig;
  Recorder<odometry_t> odom(rig.bus.lcm(), "mecanum/odometry");
  rig.start("mecanum");
  const double vx = 0.3, vy = -0.2, wz = 0.5, r = 0.05, l = 0.4;
  rig.twist("mecanum/reference", vx, vy, wz);
  rig.cycle(10);
  EXPECT_NEAR(rig.velocity("front_left"), (vx - vy - l * wz) / r, 1e-9);
  EXPECT_NEAR(rig.velocity("front_right"), (vx + vy + l * wz) / r, 1e-9);
  EXPECT_NEAR(rig.velocity("rear_right"), (vx - vy + l * wz) / r, 1e-9);
  EXPECT_NEAR(rig.velocity("rear_left"), (vx + vy - l * wz) / r, 1e-9);
  ASSERT_FALSE(odom.messages.empty());
  EXPECT_NEAR(odom.messages.back().linear.x, vx, 1e-9);
  EXPECT_NEAR(odom.messages.back().linear.y, vy, 1e-9);
  EXPECT_NEAR(odom.messages.back().angular.z, wz, 1e-9);
  // Sideways for 1 s: 0.2 m to the left in the odometry, no turn.
  DriveRig side;
  Recorder<odometry_t> odom2(side.bus.lcm(), "mecanum/odometry");
  side.start("mecanum");
  for (int k = 0; k < 10; ++k) {
    side.twist("mecanum/reference", 0, 0.2, 0);
    side.cycle(100);
  }
  EXPECT_NEAR(odom2.messages.back().position.y, 0.2, 0.002);
  EXPECT_NEAR(odom2.messages.back().position.x, 0, 1e-9);
  EXPECT_NEAR(odom2.messages.back().yaw, 0, 1e-9);
}

TEST(DriveControllers, OmniWheelsAtTheirAnglesAndOdometryByLeastSquares) {
  DriveRig rig;
  Recorder<odometry_t> odom(rig.bus.lcm(), "omni/odometry");
  Recorder<odometry_t> omni_odom(rig.bus.lcm(), "omni/odom");
  rig.start("omni");
  const double vx = 0.2, vy = 0.1, wz = -0.3, R = 0.2, r = 0.05;
  for (int k = 0; k < 5; ++k) {
    rig.twist("omni/cmd_vel", vx, vy, wz);
    rig.cycle(100);
  }
  for (int i = 0; i < 3; ++i) {
    const double a = 2 * M_PI / 3 * i;
    EXPECT_NEAR(rig.velocity("omni_" + std::to_string(i)), (std::sin(a) * vx - std::cos(a) * vy - R * wz) / r, 1e-9)
        << "wheel " << i;
  }
  EXPECT_TRUE(odom.messages.empty()) << "the omni drive's odometry is on <name>/odom";
  ASSERT_FALSE(omni_odom.messages.empty());
  EXPECT_NEAR(omni_odom.messages.back().linear.x, vx, 1e-6);
  EXPECT_NEAR(omni_odom.messages.back().linear.y, vy, 1e-6);
  EXPECT_NEAR(omni_odom.messages.back().angular.z, wz, 1e-6);
}

TEST(DriveControllers, BadParametersAreRefusedNamingTheKeyAndTheJoint) {
  // A wheel that is not a joint.
  std::string m = load_with("ackermann", "{traction_joints_names: [traction_right, no_such_wheel], "
                                         "steering_joints_names: [steer_right, steer_left], wheelbase: 0.5, "
                                         "traction_track_width: 0.4, traction_wheels_radius: 0.1}");
  EXPECT_TRUE(has(m, "ackermann/traction_joints_names: controller 'ackermann': joint 'no_such_wheel' is not in the URDF"))
      << m;
  // A steering joint without a position interface.
  m = load_with("bicycle", "{traction_joints_names: [traction], steering_joints_names: [pusher], wheelbase: 0.5, "
                           "traction_wheel_radius: 0.1}");
  EXPECT_TRUE(has(m, "bicycle/steering_joints_names: controller 'bicycle' needs PositionJointInterface on joint "
                     "'pusher'"))
      << m;
  // A passive joint: nothing drives it.
  m = load_with("tricycle", "{traction_joint_name: caster, steering_joint_name: steer, wheelbase: 0.5, "
                            "wheel_radius: 0.1}");
  EXPECT_TRUE(has(m, "tricycle/traction_joint_name: controller 'tricycle' needs VelocityJointInterface on joint "
                     "'caster'"))
      << m;
  // Zero wheel radii.
  m = load_with("ackermann", "{traction_joints_names: [traction_right, traction_left], steering_joints_names: "
                             "[steer_right, steer_left], wheelbase: 0.5, traction_track_width: 0.4, "
                             "traction_wheels_radius: 0}");
  EXPECT_TRUE(has(m, "ackermann/traction_wheels_radius: 0 m: must be > 0 (the radius of traction wheels "
                     "'traction_right', 'traction_left')"))
      << m;
  m = load_with("tricycle", "{traction_joint_name: traction, steering_joint_name: steer, wheelbase: 0.5, "
                            "wheel_radius: 0.0}");
  EXPECT_TRUE(has(m, "tricycle/wheel_radius: 0 m: must be > 0 (the radius of the wheel 'traction' drives)")) << m;
  m = load_with("mecanum", "{front_left_wheel_command_joint_name: front_left, front_right_wheel_command_joint_name: "
                           "front_right, rear_right_wheel_command_joint_name: rear_right, "
                           "rear_left_wheel_command_joint_name: rear_left, kinematics: {wheels_radius: 0, "
                           "sum_of_robot_center_projection_on_X_Y_axis: 0.4}}");
  EXPECT_TRUE(has(m, "mecanum/kinematics/wheels_radius: 0 m: must be > 0 (the radius of the wheels 'front_left'"))
      << m;
  m = load_with("omni", "{wheel_names: [omni_0, omni_1, omni_2], robot_radius: 0.2, wheel_radius: -0.05}");
  EXPECT_TRUE(has(m, "omni/wheel_radius: -0.05 m: must be > 0 (the radius of the wheels 'omni_0'")) << m;
  // The wrong number of joints for the kinematics.
  m = load_with("ackermann", "{traction_joints_names: [traction], steering_joints_names: [steer_right, steer_left], "
                             "wheelbase: 0.5, traction_track_width: 0.4, traction_wheels_radius: 0.1}");
  EXPECT_TRUE(has(m, "ackermann/traction_joints_names: [traction]: the Ackermann drive takes 2 joints, right then "
                     "left"))
      << m;
  m = load_with("omni", "{wheel_names: [omni_0, omni_1], robot_radius: 0.2, wheel_radius: 0.05}");
  EXPECT_TRUE(has(m, "omni/wheel_names: 2 wheel(s): an omni base needs three or more")) << m;
}

}  // namespace
