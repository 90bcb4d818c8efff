// ros2_control_demos' examples from ../shared/ros2_robots, each with its own unchanged xacro and controllers YAML,
// driven by the command its userdoc gives, in lockstep: example 11's car on its bicycle steering reference, example
// 12's three-level controller chain, example 16's diff drive chained into two wheel PIDs (its demo hardware played
// as mock hardware), and the gz variant of example 16 (effort PIDs under the diff drive) in Bullet, odometry against
// ground truth. Skipped when the folder is absent; our own robots cover each trait without it
// (test/e2e/drives_test.cpp, test/controller_manager/chaining_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/e2e/mobile_session.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lcm_control::testing {
namespace {

// A demo's robot: its package's xacro and its config/ YAML, with its pkgs/ on the package path.
MobileSession demo(const std::string& dir, const std::string& folder, const std::string& package,
                   const std::string& xacro, const std::string& yaml, std::vector<std::string> controllers,
                   const std::string& command, const std::string& odometry, double rate_hz) {
  const std::string root = dir + "/" + folder;
  return MobileSession(root + "/pkgs/" + package + "/urdf/" + xacro, root + "/config/" + yaml, std::move(controllers),
                       command, odometry, {"--package-path", root + "/pkgs"}, rate_hz);
}

// Example 11 (CarlikeBot): `ros2 topic pub --rate 30 /bicycle_steering_controller/reference` with 1 m/s and
// 0.1 rad/s. The virtual steering joint holds atan(wheelbase * w / v), the virtual traction wheel turns at v / r,
// the four real wheels mimic them, and the odometry runs a circle of radius v / w.
void carlike_circles(const std::vector<std::string>& sim_flags) {
  NEED_ROS2_ROBOTS(dir);
  MobileSession s = demo(dir, "demo_carlike", "ros2_control_demo_example_11", "carlikebot.urdf.xacro",
                         "carlikebot_controllers.yaml", {"joint_state_broadcaster", "bicycle_steering_controller"},
                         "bicycle_steering_controller/reference", "bicycle_steering_controller/odometry", 10);
  ASSERT_NO_FATAL_FAILURE(s.start(sim_flags));
  ASSERT_NO_FATAL_FAILURE(s.idle(10));
  const Pose2 odom0 = s.odometry();
  const double v = 1.0, w = 0.1, wheelbase = 0.325, radius = 0.05, seconds = 10;
  ASSERT_NO_FATAL_FAILURE(s.drive(v, 0, w, seconds, {}, false));
  const double steering = s.position("virtual_front_wheel_joint"), traction = s.velocity("virtual_rear_wheel_joint");
  std::printf("example 11: steering %.5f rad (atan(L w / v) %.5f), traction %.4f rad/s (v / r %.4f); front wheels "
              "%.5f %.5f rad, rear wheels %.4f %.4f rad/s\n",
              steering, std::atan(wheelbase * w / v), traction, v / radius, s.position("front_left_wheel_joint"),
              s.position("front_right_wheel_joint"), s.velocity("rear_left_wheel_joint"),
              s.velocity("rear_right_wheel_joint"));
  EXPECT_NEAR(steering, std::atan(wheelbase * w / v), 0.01 * std::atan(wheelbase * w / v)) << s.output();
  EXPECT_NEAR(traction, v / radius, 0.01 * v / radius);
  EXPECT_NEAR(s.position("front_left_wheel_joint"), steering, 1e-9) << "the real wheels mimic the virtual ones";
  EXPECT_NEAR(s.velocity("rear_right_wheel_joint"), traction, 1e-9);
  // On the circle of radius v / w that starts at the first pose, heading w * t.
  const Pose2 o = relative(odom0, s.odometry());
  const double r = v / w, off_circle = std::abs(std::hypot(o.x, o.y - r) - r);
  std::printf("example 11: odometry after %.0f s at (%.4f, %.4f, %.4f rad): %.4f m off the %.0f m circle\n", seconds,
              o.x, o.y, o.yaw, off_circle, r);
  EXPECT_NEAR(o.yaw, w * seconds, 0.02 * w * seconds);
  EXPECT_LT(off_circle, 0.02 * v * seconds) << "within 2 % of the path";
  ASSERT_NO_FATAL_FAILURE(s.drive(0, 0, 0, 0));
}

TEST(Ros2Demos, Example11CarlikeBotDrivesItsBicycleReferenceOnACircle) { carlike_circles({}); }

// The same in Bullet: the joints and the odometry as on mock hardware. Its ground truth is not compared: the URDF's
// front wheels only steer (no joint to roll on), so in any physics engine they drag and the car barely moves
// (7.5 cm in these 10 s); upstream runs this example on its mock-like hardware only.
TEST(Ros2Demos, Example11CarlikeBotInBulletDrivesItsBicycleReferenceOnACircle) { carlike_circles({"--physics"}); }

// Example 12: the chain forward_position_controller -> position_controller -> joint{1,2}_position_controller ->
// joint1/joint2, spawned in the order its launch files do; a command on the top reaches the joints.
// The whole chain in one spawner call, as the demo's launch file spawns it, or all or nothing (--activate-as-group).
void example12(const std::string& dir, bool as_group) {
  const std::string root = dir + "/demo_chaining";
  LockstepSession robot(root + "/pkgs/ros2_control_demo_example_12/urdf/rrbot.urdf.xacro",
                        root + "/config/rrbot_chained_controllers.yaml", {"--package-path", root + "/pkgs"});
  std::vector<std::string> spawned = {"joint_state_broadcaster", "joint1_position_controller",
                                      "joint2_position_controller", "position_controller",
                                      "forward_position_controller"};
  if (as_group) spawned.push_back("--activate-as-group");
  ASSERT_NO_FATAL_FAILURE(robot.start(spawned));
  lcm::LCM lc(robot.url());
  Recorder<joint_state_t> states(lc, "joint_states");
  float64_array_t command{};
  command.size = 2;
  command.data = {0.5, -0.25};
  auto at = [&](const std::string& joint) -> double {
    const joint_state_t& m = states.messages.back();
    for (int k = 0; k < m.num_joints; ++k)
      if (m.name[size_t(k)] == joint) return m.position[size_t(k)];
    return NAN;
  };
  ASSERT_TRUE(pump_until(lc,
                         [&] {
                           lc.publish("forward_position_controller/command", &command);
                           return !states.messages.empty() && at("joint1") == 0.5 && at("joint2") == -0.25;
                         },
                         15))
      << robot.cm_output() << robot.sim_output();
  std::string chains;
  EXPECT_EQ(robot.run({"cmctl", "view-controller-chains"}, &chains), 0) << chains;
  std::printf("%s", chains.c_str());
  EXPECT_NE(chains.find("writes position_controller/joint1_position_controller/joint1/position -> position_controller"),
            std::string::npos)
      << chains;
  EXPECT_NE(chains.find("writes joint2_position_controller/joint2/position -> joint2_position_controller"),
            std::string::npos);
  std::string listed;
  EXPECT_EQ(robot.run({"cmctl", "list-controllers", "--verbose"}, &listed), 0) << listed;
  std::printf("%s", listed.c_str());
  EXPECT_TRUE(std::regex_search(listed, std::regex(R"(\nposition_controller .* active .* yes +position_controller/)")))
      << "chained mode and its reference interfaces: " << listed;
}

TEST(Ros2Demos, Example12ThreeLevelChainPassesTheForwardCommandToTheJoints) {
  NEED_ROS2_ROBOTS(dir);
  example12(dir, false);
}

TEST(Ros2Demos, Example12ChainActivatesAsAGroup) {
  NEED_ROS2_ROBOTS(dir);
  example12(dir, true);
}

// Example 16: `ros2 topic pub --rate 10 /cmd_vel` into the diff drive, whose wheel velocities are the references of
// two pid_controllers (quoted-key flow-map gains, feedforward 0.95) that command the wheels. Within the wheels'
// URDF velocity limit (1 rad/s) the PIDs bring each wheel to its reference and the mock hardware integrates it.
TEST(Ros2Demos, Example16DiffDriveChainedIntoWheelPidsBringsEachWheelToItsReference) {
  NEED_ROS2_ROBOTS(dir);
  MobileSession s = demo(dir, "demo_diffbot_chained_pid", "ros2_control_demo_example_16", "diffbot.urdf.xacro",
                         "diffbot_chained_controllers.yaml",
                         {"joint_state_broadcaster", "pid_controller_left_wheel_joint",
                          "pid_controller_right_wheel_joint", "diffbot_base_controller"},
                         "diffbot_base_controller/cmd_vel", "diffbot_base_controller/odom", 10);
  ASSERT_NO_FATAL_FAILURE(s.start());
  ASSERT_NO_FATAL_FAILURE(s.idle(10));
  const double v = 0.01, w = 0.05, separation = 0.10, radius = 0.015;
  const double left_ref = (v - w * separation / 2) / radius, right_ref = (v + w * separation / 2) / radius;
  const double left0 = s.position("left_wheel_joint");
  ASSERT_NO_FATAL_FAILURE(s.drive(v, 0, w, 6, {}, false));
  const double left = s.velocity("left_wheel_joint"), right = s.velocity("right_wheel_joint");
  const double turned = s.position("left_wheel_joint") - left0;
  std::printf("example 16: wheels %.4f and %.4f rad/s for references %.4f and %.4f; the left wheel turned %.3f rad\n",
              left, right, left_ref, right_ref, turned);
  EXPECT_NEAR(left, left_ref, 0.01 * left_ref) << s.output();
  EXPECT_NEAR(right, right_ref, 0.01 * right_ref);
  EXPECT_GT(turned, 0.8 * left_ref * 6) << "the demo's hardware integrates the wheel's velocity";
  ASSERT_NO_FATAL_FAILURE(s.drive(0, 0, 0, 0));
  ASSERT_NO_FATAL_FAILURE(s.idle(30));
  EXPECT_NEAR(s.velocity("left_wheel_joint"), 0.0, 0.01) << "stopped with the twist";
  // The userdoc's own command, 0.7 m/s and 1 rad/s: references of 43 and 50 rad/s, each wheel held at its URDF
  // velocity limit of 1 rad/s (the PID clamps its command there, as ros2_control's enforce_command_limits does);
  // the odometry, open_loop, follows the command.
  ASSERT_NO_FATAL_FAILURE(s.drive(0.7, 0, 1.0, 3, {}, false));
  const odometry_t& odom = s.odometry_messages().back();
  std::printf("example 16, the userdoc's command: odometry %.3f m/s, %.3f rad/s; wheels %.4f and %.4f rad/s\n",
              odom.linear.x, odom.angular.z, s.velocity("left_wheel_joint"), s.velocity("right_wheel_joint"));
  EXPECT_NEAR(odom.linear.x, 0.7, 1e-6);
  EXPECT_NEAR(odom.angular.z, 1.0, 1e-6);
  EXPECT_NEAR(s.velocity("left_wheel_joint"), 1.0, 1e-9);
  EXPECT_NEAR(s.velocity("right_wheel_joint"), 1.0, 1e-9);
  ASSERT_NO_FATAL_FAILURE(s.drive(0, 0, 0, 0));
}

// The gz variant of example 16 (ros2_control_demos PR #786) in Bullet: one pid_controller for both wheels on
// effort, the diff drive on its references, odometry from the wheels. It rests, drives 1 m, and ground truth
// agrees with odometry within 2 %.
TEST(Ros2Demos, Example16GzVariantInBulletDrivesAMetreOdometryWithinTwoPercentOfGroundTruth) {
  NEED_ROS2_ROBOTS(dir);
  MobileSession s = demo(dir, "demo_diffbot_chained_pid_gz", "ros2_control_demo_example_17", "diffbot.urdf.xacro",
                         "diffbot_chained_controllers.yaml",
                         {"joint_state_broadcaster", "wheel_pids", "diffbot_base_controller"},
                         "diffbot_base_controller/cmd_vel", "diffbot_base_controller/odom", 100);
  ASSERT_NO_FATAL_FAILURE(s.start());
  ASSERT_NO_FATAL_FAILURE(s.idle(100));
  EXPECT_LT(std::abs(s.velocity("left_wheel_joint")), 0.01) << "at rest with no command: " << s.output();
  const Pose2 odom0 = s.odometry(), truth0 = s.truth();
  ASSERT_NO_FATAL_FAILURE(s.drive(0.1, 0, 0, 20, [&] { return relative(odom0, s.odometry()).x >= 1.0; }));
  ASSERT_NO_FATAL_FAILURE(s.idle(100));
  const Pose2 t = relative(truth0, s.truth()), o = relative(odom0, s.odometry());
  const double gap = std::hypot(t.x - o.x, t.y - o.y);
  std::printf("example 16 (gz): odometry (%.4f, %.4f), ground truth (%.4f, %.4f): %.4f m apart\n", o.x, o.y, t.x, t.y,
              gap);
  EXPECT_NEAR(o.x, 1.0, 0.05) << "stopped once its odometry said 1 m";
  EXPECT_LT(gap, 0.02 * std::hypot(o.x, o.y)) << "ground truth within 2 % of odometry";
}

}  // namespace
}  // namespace lcm_control::testing
