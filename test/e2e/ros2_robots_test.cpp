// ROS 2 robots from their own unchanged packages (../shared/ros2_robots: gz_ros2_control's cart, ros2_control_demos'
// rrbot example 1, Universal Robots' UR5e as ur_simulation_gz loads it), end to end with the real programs in
// lockstep. Skipped when the folder is absent; the project's own ROS 2 test robots cover each trait without it
// (test/controller_manager/ros2_controllers_test.cpp, test/sim_server, test/e2e/interface_switch_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <numeric>

#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/imu_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "rt/clock.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

double position_of(const joint_state_t& s, const std::string& joint) {
  for (int k = 0; k < s.num_joints; ++k)
    if (s.name[k] == joint) return s.position[k];
  return NAN;
}

using Session = lt::LockstepSession;

// The newest joint_states once `done` holds for it (at most timeout_s).
joint_state_t state_when(const Session& s, const std::function<bool(const joint_state_t&)>& done,
                         double timeout_s = 20) {
  lcm::LCM lc(s.url());
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  lt::pump_until(lc, [&] { return !states.messages.empty() && done(states.messages.back()); }, timeout_s);
  return states.messages.empty() ? joint_state_t{} : states.messages.back();
}

}  // namespace

TEST(Ros2Robots, GzCartOnPositionReachesATrajectoryGoalWithinAMillimetre) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/gz_cart/pkgs/gz_ros2_control_demos";
  Session s(pkg + "/urdf/test_cart_position.xacro.urdf", pkg + "/config/cart_controller_position.yaml", {});
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "joint_trajectory_controller"}));
  // initial_value 5.0 is the start pose, as gz_ros2_control teleports the cart there.
  const joint_state_t first = state_when(s, [](const joint_state_t&) { return true; });
  EXPECT_NEAR(position_of(first, "slider_to_cart"), 5.0, 1e-3);
  std::string out;
  ASSERT_EQ(s.run({"send-trajectory", "joint_trajectory_controller", "--point", "1:6.0", "--point", "2:4.0"}, &out), 0)
      << out << s.sim_output();
  EXPECT_NE(out.find("SUCCEEDED"), std::string::npos) << out;
  const joint_state_t end = state_when(s, [](const joint_state_t& m) { return m.num_joints > 0; });
  EXPECT_NEAR(position_of(end, "slider_to_cart"), 4.0, 1e-3);
}

TEST(Ros2Robots, RrbotExample1OnMockHardwareTakesForwardPositionsWithItsVarPrefix) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/rrbot9/pkgs/ros2_control_demo_example_1";
  Session s(pkg + "/urdf/rrbot.urdf.xacro", pkg + "/config/rrbot_controllers.yaml",
            {"--package-path", dir + "/rrbot9/pkgs", "--arg", "joint_prefix=joint"});
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "forward_position_controller"}));
  EXPECT_TRUE(s.sim_output().find("mock hardware") != std::string::npos) << s.sim_output();
  lcm::LCM lc(s.url());
  float64_array_t cmd{};
  cmd.data = {0.785, -0.785};
  cmd.size = 2;
  lc.publish("forward_position_controller/command", &cmd);
  const joint_state_t end = state_when(s, [](const joint_state_t& m) {
    return std::abs(position_of(m, "joint1") - 0.785) < 1e-9 && std::abs(position_of(m, "joint2") + 0.785) < 1e-9;
  });
  EXPECT_NEAR(position_of(end, "joint1"), 0.785, 1e-9);
  EXPECT_NEAR(position_of(end, "joint2"), -0.785, 1e-9);
}

TEST(Ros2Robots, Ur5eTrajectoryGoalSucceedsAndAVelocityControllerSwitchesTheInterface) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkgs = dir + "/ur5e/pkgs";
  Session s(pkgs + "/ur_simulation_gz/urdf/ur_gz.urdf.xacro", pkgs + "/ur_simulation_gz/config/ur_controllers.yaml",
            {"--package-path", pkgs, "--xacro-arg", "name:=ur", "--xacro-arg", "ur_type:=ur5e", "--xacro-arg",
             "safety_limits:=true", "--xacro-arg", "simulation_controllers:=" + pkgs +
                                                       "/ur_simulation_gz/config/ur_controllers.yaml"});
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "joint_trajectory_controller"}));
  std::string out;
  ASSERT_EQ(s.run({"send-trajectory", "joint_trajectory_controller", "--relative", "--point",
                   "2:0.3,-0.3,0.3,0.3,0.3,0.3"},
                  &out),
            0)
      << out << s.sim_output();
  EXPECT_NE(out.find("SUCCEEDED"), std::string::npos) << out;

  ASSERT_EQ(s.run({"cmctl", "load-controller", "forward_velocity_controller"}, &out), 0) << out;
  ASSERT_EQ(s.run({"cmctl", "switch-controllers", "--activate", "forward_velocity_controller", "--deactivate",
                   "joint_trajectory_controller"},
                  &out),
            0)
      << out;
  ASSERT_EQ(s.run({"cmctl", "list-hardware-interfaces"}, &out), 0) << out;
  EXPECT_NE(out.find("shoulder_pan_joint/velocity [available] [claimed by forward_velocity_controller]"),
            std::string::npos)
      << out;
  const double before = position_of(state_when(s, [](const joint_state_t&) { return true; }), "elbow_joint");
  lcm::LCM lc(s.url());
  float64_array_t v{};
  v.data = {0, 0, 0.2, 0, 0, 0};
  v.size = 6;
  lc.publish("forward_velocity_controller/command", &v);
  const joint_state_t moved = state_when(s, [&](const joint_state_t& m) {
    return position_of(m, "elbow_joint") > before + 0.1;
  });
  EXPECT_GT(position_of(moved, "elbow_joint"), before + 0.1) << s.sim_output();
}

namespace {

// One forward command (float64_array_t) to `controller`.
void forward(const Session& s, const std::string& controller, std::vector<double> values) {
  lcm::LCM lc(s.url());
  float64_array_t m{};
  m.size = static_cast<int32_t>(values.size());
  m.data = std::move(values);
  lc.publish(controller + "/command", &m);
}

}  // namespace

TEST(Ros2Robots, GzCartOnVelocityAndOnEffortMovesTheCartAsCommanded) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/gz_cart/pkgs/gz_ros2_control_demos";
  {
    Session s(pkg + "/urdf/test_cart_velocity.xacro.urdf", pkg + "/config/cart_controller_velocity.yaml", {});
    ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "velocity_controller"}));
    const double x0 = position_of(state_when(s, [](const joint_state_t&) { return true; }), "slider_to_cart");
    forward(s, "velocity_controller", {1.5});
    const joint_state_t m = state_when(s, [&](const joint_state_t& m) { return position_of(m, "slider_to_cart") > x0 + 3; });
    EXPECT_GT(position_of(m, "slider_to_cart"), x0 + 3);
    for (int k = 0; k < m.num_joints; ++k) {
      if (m.name[k] == "slider_to_cart") {
        EXPECT_NEAR(m.velocity[k], 1.5, 1e-3);
      }
    }
  }
  {
    Session s(pkg + "/urdf/test_cart_effort.xacro.urdf", pkg + "/config/cart_controller_effort.yaml", {});
    ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "effort_controller"}));
    const double x0 = position_of(state_when(s, [](const joint_state_t&) { return true; }), "slider_to_cart");
    forward(s, "effort_controller", {-2.0});  // 2 N on the 1 kg cart: 1 m/s^2 backwards
    const joint_state_t m = state_when(s, [&](const joint_state_t& m) { return position_of(m, "slider_to_cart") < x0 - 1; });
    EXPECT_LT(position_of(m, "slider_to_cart"), x0 - 1);
  }
}

TEST(Ros2Robots, GzMimicGripperFingersMoveTogetherAndStopAtTheCommandedOpening) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/gz_gripper_mimic/pkgs/gz_ros2_control_demos";
  for (const std::string variant : {"position", "effort"}) {
    SCOPED_TRACE(variant);
    Session s(pkg + "/urdf/test_gripper_mimic_joint_" + variant + ".xacro.urdf",
              pkg + "/config/gripper_controller_" + variant + ".yaml", {});
    ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "gripper_controller"}));
    // position: to 0.3; effort: 50 N opens it to its limit 0.38.
    const double target = variant == "position" ? 0.3 : 0.38;
    forward(s, "gripper_controller", {variant == "position" ? 0.3 : 50.0});
    const joint_state_t m = state_when(s, [&](const joint_state_t& m) {
      return std::abs(position_of(m, "right_finger_joint") - target) < 2e-3 &&
             std::abs(position_of(m, "left_finger_joint") - target) < 2e-3;
    });
    EXPECT_NEAR(position_of(m, "right_finger_joint"), target, 2e-3) << s.sim_output();
    EXPECT_NEAR(position_of(m, "left_finger_joint"), position_of(m, "right_finger_joint"), 2e-3);
  }
}

TEST(Ros2Robots, RrbotExample9InGazeboTakesForwardPositions) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/rrbot9/pkgs/ros2_control_demo_example_9";
  Session s(pkg + "/urdf/rrbot.urdf.xacro", pkg + "/config/rrbot_controllers.yaml",
            {"--package-path", dir + "/rrbot9/pkgs", "--xacro-arg", "use_gazebo:=true"});
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "forward_position_controller"}));
  EXPECT_EQ(s.sim_output().find("mock hardware"), std::string::npos) << s.sim_output();
  forward(s, "forward_position_controller", {0.785, -0.785});
  const joint_state_t m = state_when(s, [](const joint_state_t& m) {
    return std::abs(position_of(m, "joint1") - 0.785) < 1e-3 && std::abs(position_of(m, "joint2") + 0.785) < 1e-3;
  });
  EXPECT_NEAR(position_of(m, "joint1"), 0.785, 1e-3) << s.sim_output();
  EXPECT_NEAR(position_of(m, "joint2"), -0.785, 1e-3);
}

TEST(Ros2Robots, GzDiffDriveAtATenthOfAMetrePerSecondForFiveSecondsGoesHalfAMetre) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/gz_diff_drive/pkgs/gz_ros2_control_demos";
  Session s(pkg + "/urdf/test_diff_drive.xacro.urdf", pkg + "/config/diff_drive_controller_velocity.yaml", {});
  s.start_controller_manager();
  ASSERT_NO_FATAL_FAILURE(s.spawn({"joint_state_broadcaster", "diff_drive_base_controller"}));
  s.start_sim({"--floating-base"}, 30);  // real time: cmd_vel_timeout is 0.5 s of sim time
  lcm::LCM lc(s.url());
  lt::Recorder<odometry_t> odom(lc, "diff_drive_base_controller/odom"), truth(lc, "sim_server/base_pose");
  lt::pump_until(lc, [&] { return !odom.messages.empty() && !truth.messages.empty(); }, 10);
  ASSERT_FALSE(odom.messages.empty() || truth.messages.empty()) << s.sim_output();
  lt::pump_until(lc, [] { return false; }, 1.0);  // settled on its wheels
  const odometry_t odom0 = odom.messages.back(), truth0 = truth.messages.back();
  twist_t go{};
  go.linear.x = 0.1;
  const int64_t end = monotonic_us() + 5000000;
  while (monotonic_us() < end) {
    lc.publish("diff_drive_base_controller/cmd_vel", &go);
    lt::pump_until(lc, [] { return false; }, 0.05);
  }
  twist_t stop{};
  lc.publish("diff_drive_base_controller/cmd_vel", &stop);
  lt::pump_until(lc, [] { return false; }, 1.0);
  const double odom_d = std::hypot(odom.messages.back().position.x - odom0.position.x,
                                   odom.messages.back().position.y - odom0.position.y);
  const double truth_d = std::hypot(truth.messages.back().position.x - truth0.position.x,
                                    truth.messages.back().position.y - truth0.position.y);
  std::printf("diff drive: odometry %.4f m, ground truth %.4f m (goal 0.5 m +- 5 %%)\n", odom_d, truth_d);
  EXPECT_NEAR(odom_d, 0.5, 0.025);
  EXPECT_NEAR(truth_d, 0.5, 0.025) << s.sim_output();
}

TEST(Ros2Robots, Robotiq2f85GripperControllerOpensAndClosesWithItsFiveMimicJointsFollowing) {
  NEED_ROS2_ROBOTS(dir);
  const std::string r = dir + "/robotiq_2f85";
  Session s(r + "/derived/robotiq_2f_85_sim_gazebo.urdf.xacro", r + "/config/robotiq_controllers.yaml",
            {"--package-path", r + "/pkgs"});
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "robotiq_gripper_controller"}));
  const std::vector<std::pair<std::string, double>> mimics = {
      {"robotiq_85_right_knuckle_joint", -1},      {"robotiq_85_left_inner_knuckle_joint", 1},
      {"robotiq_85_right_inner_knuckle_joint", -1}, {"robotiq_85_left_finger_tip_joint", -1},
      {"robotiq_85_right_finger_tip_joint", 1}};
  for (const double goal : {0.0, 0.5}) {
    SCOPED_TRACE(goal);
    std::string out;
    const int rc = s.run({"gripper", "robotiq_gripper_controller", "--position", std::to_string(goal)}, &out);
    EXPECT_EQ(rc, 0) << out << s.sim_output();
    const joint_state_t m = state_when(s, [](const joint_state_t& m) { return m.num_joints >= 6; });
    const double q = position_of(m, "robotiq_85_left_knuckle_joint");
    EXPECT_NEAR(q, goal, 0.02) << out;  // the YAML's goal_tolerance
    for (const auto& [joint, multiplier] : mimics) EXPECT_NEAR(position_of(m, joint), multiplier * q, 1e-3) << joint;
  }
}

namespace {

// imu_sensor_broadcaster's messages by utime until `count` have come (at most 60 s).
std::map<int64_t, imu_t> imu_readings(const Session& s, size_t count) {
  lcm::LCM lc(s.url());
  lt::Recorder<imu_t> imu(lc, "imu_sensor_broadcaster/imu");
  lt::pump_until(lc, [&] { return imu.messages.size() >= count; }, 60);
  std::map<int64_t, imu_t> by_time;
  for (const imu_t& m : imu.messages) by_time[m.utime] = m;
  return by_time;
}

}  // namespace

TEST(Ros2Robots, GzCartImuBroadcasterPublishesAtTheControllerRateExactWithoutNoiseRepeatableWithIt) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/gz_cart/pkgs/gz_ros2_control_demos";
  const std::string config = pkg + "/config/cart_controller_velocity.yaml";
  {
    Session s(pkg + "/urdf/test_cart_velocity.xacro.urdf", config, {});
    ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "imu_sensor_broadcaster"}));
    const auto got = imu_readings(s, 2000);
    ASSERT_GE(got.size(), 1000u) << s.sim_output();
    int64_t last = -1;
    size_t consecutive = 0;
    for (const auto& [t, m] : got) {
      consecutive += last >= 0 && t - last == 1000;  // update_rate 1000 Hz: one a step
      last = t;
      EXPECT_EQ(m.frame_id, "imu");
      EXPECT_NEAR(m.linear_acceleration.x, 0, 1e-9);  // held still by gz_ros2_control's hold_joints
      EXPECT_NEAR(m.linear_acceleration.y, 0, 1e-9);
      EXPECT_NEAR(m.linear_acceleration.z, 9.81, 1e-9);
      EXPECT_NEAR(m.angular_velocity.x, 0, 1e-12);
      EXPECT_NEAR(m.orientation.w, 1, 1e-12);
      if (::testing::Test::HasFailure()) break;
    }
    std::printf("noise off: %zu readings, %zu one step after the one before\n", got.size(), consecutive);
    EXPECT_GT(consecutive, got.size() * 9 / 10);
  }
  // The same cart with <noise> on its IMU's accelerometer (a scratch copy; the package stays as shipped).
  std::ifstream in(pkg + "/urdf/test_cart_velocity.xacro.urdf");
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string noise = "<noise type=\"gaussian\"><mean>0</mean><stddev>0.05</stddev></noise>";
  const auto at = urdf.find("<topic>imu</topic>");
  ASSERT_NE(at, std::string::npos);
  urdf.insert(at, "<imu><linear_acceleration><x>" + noise + "</x><y>" + noise + "</y><z>" + noise +
                      "</z></linear_acceleration></imu>");
  const std::string noisy = lt::temp_dir("gz_cart_noise") + "/test_cart_velocity_noisy.urdf";
  std::ofstream(noisy) << urdf;
  std::map<int64_t, imu_t> runs[2];
  for (auto& run : runs) {
    Session s(noisy, config, {});
    ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_broadcaster", "imu_sensor_broadcaster"}));
    run = imu_readings(s, 10500);
  }
  std::vector<double> z;
  size_t same = 0, compared = 0;
  for (const auto& [t, m] : runs[0]) {
    z.push_back(m.linear_acceleration.z);
    const auto other = runs[1].find(t);
    if (other == runs[1].end()) continue;
    ++compared;
    same += other->second.linear_acceleration.x == m.linear_acceleration.x &&
            other->second.linear_acceleration.z == m.linear_acceleration.z;
  }
  const double mean = std::accumulate(z.begin(), z.end(), 0.0) / double(z.size());
  double var = 0;
  for (double v : z) var += (v - mean) * (v - mean);
  const double sd = std::sqrt(var / double(z.size() - 1));
  std::printf("noise 0.05: %zu readings, z mean %.5f sd %.5f; %zu of %zu at the same step bit-identical\n", z.size(),
              mean, sd, same, compared);
  EXPECT_GE(z.size(), 10000u);
  EXPECT_NEAR(sd, 0.05, 0.005);
  EXPECT_NEAR(mean, 9.81, 0.005);
  EXPECT_GT(compared, 9000u);
  EXPECT_EQ(same, compared);
}

