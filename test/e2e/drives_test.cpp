// The drives of ros2_controllers on our own mobile robots (test/robots/mobile), in lockstep with the simulation
// paused and stepped exactly: a car on ackermann_steering_controller and on bicycle_steering_controller drives a
// 2 m circle, a tricycle, a mecanum and an omni base drive squares steered by their own odometry, and a round base
// with a Z_UP Collada bumper and sprung wheel drops rests level and drives 1 m. Ground truth is sim_server/base_pose
// (the free base's root link, which the robots put where their odometry's reference point is).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "test/e2e/mobile_session.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"
#include "tools/lib/clients/sim_client.hpp"

namespace lcm_control::testing {
namespace {

std::string mobile(const std::string& file) { return source("test/robots/mobile/" + file); }

// One of our own mobile robots (test/robots/mobile) with joint_state_broadcaster and its drive.
class DriveSession : public MobileSession {
 public:
  DriveSession(const std::string& urdf, const std::string& config, const std::string& controller,
               const std::string& command, const std::string& odometry, std::vector<std::string> xacro_args = {})
      : MobileSession(mobile(urdf), mobile(config), {"joint_state_broadcaster", controller}, controller + "/" + command,
                      controller + "/" + odometry, xacro_flags(xacro_args)) {}

 private:
  static std::vector<std::string> xacro_flags(const std::vector<std::string>& args) {
    std::vector<std::string> out;
    for (const auto& a : args) out.insert(out.end(), {"--xacro-arg", a});
    return out;
  }
};

// A lap of a circle of radius 2 m at 0.5 m/s: odometry against ground truth all the way (within 2 % of the path),
// and the steering angle the controller holds against atan(wheelbase / R) (within 1 %).
void circle_lap(DriveSession& s, const std::function<double()>& middle_steering) {
  ASSERT_NO_FATAL_FAILURE(s.start());
  ASSERT_NO_FATAL_FAILURE(s.idle(50));
  const Pose2 odom0 = s.odometry(), truth0 = s.truth();
  const double v = 0.5, r = 2.0, w = v / r, wheelbase = 0.5, lap = 2 * M_PI * r;
  const size_t first = s.truth_messages().size();
  ASSERT_NO_FATAL_FAILURE(s.drive(v, 0, w, 5.0, {}, false));
  const double steering = middle_steering(), expected = std::atan(wheelbase / r);
  ASSERT_NO_FATAL_FAILURE(s.drive(v, 0, w, lap / v - 5.0));
  ASSERT_NO_FATAL_FAILURE(s.idle(100));
  // Odometry and ground truth at the same sim time, both from where they were at the start.
  std::map<int64_t, Pose2> odom_at;
  for (const odometry_t& m : s.odometry_messages()) odom_at[m.utime] = relative(odom0, pose_of(m));
  double worst = 0, travelled = 0, max_r = 0, min_r = 1e9;
  Pose2 last = relative(truth0, pose_of(s.truth_messages()[first]));
  for (size_t k = first; k < s.truth_messages().size(); ++k) {
    const Pose2 t = relative(truth0, pose_of(s.truth_messages()[k]));
    travelled += std::hypot(t.x - last.x, t.y - last.y);
    last = t;
    const double radius = std::hypot(t.x, t.y - r);  // from the circle's centre, 2 m to the left of the start
    if (travelled > 1.0) max_r = std::max(max_r, radius), min_r = std::min(min_r, radius);
    const auto o = odom_at.find(s.truth_messages()[k].utime);
    if (o != odom_at.end()) worst = std::max(worst, std::hypot(o->second.x - t.x, o->second.y - t.y));
  }
  const Pose2 end_truth = relative(truth0, s.truth()), end_odom = relative(odom0, s.odometry());
  std::printf("lap: ground truth travelled %.3f m, radius %.4f..%.4f m, ends at (%.4f, %.4f, %.4f rad); odometry "
              "ends at (%.4f, %.4f, %.4f rad); worst odometry error %.4f m (%.2f %% of the path); middle steering "
              "%.5f rad against atan(L/R) %.5f\n",
              travelled, min_r, max_r, end_truth.x, end_truth.y, end_truth.yaw, end_odom.x, end_odom.y, end_odom.yaw,
              worst, 100 * worst / lap, steering, expected);
  EXPECT_NEAR(travelled, lap, 0.05 * lap) << "a lap at 0.5 m/s";
  EXPECT_LT(worst, 0.02 * lap) << "odometry within 2 % of the path of ground truth";
  EXPECT_NEAR(steering, expected, 0.01 * expected) << "atan(wheelbase / R)";
  EXPECT_NEAR(min_r, r, 0.05 * r);
  EXPECT_NEAR(max_r, r, 0.05 * r);
  EXPECT_LT(std::hypot(end_truth.x, end_truth.y), 0.05 * lap) << "back near the start after a lap";
}

TEST(Drives, AnAckermannCarDrivesATwoMetreCircleItsOdometryWithinTwoPercentAndItsSteeringAtAtanLOverR) {
  DriveSession s("car.urdf.xacro", "car_ackermann.yaml", "ackermann_steering_controller", "reference", "odometry");
  circle_lap(s, [&] {
    // The two steering angles as the one middle wheel's: cot(middle) is the mean of their cotangents.
    const double right = s.position("front_right_steering_joint"), left = s.position("front_left_steering_joint");
    EXPECT_GT(left, right) << "turning left, the inner (left) wheel steers more";
    return std::atan(2 / (1 / std::tan(right) + 1 / std::tan(left)));
  });
}

TEST(Drives, ABicycleSteeredCarOnVirtualJointsDrivesATwoMetreCircleItsOdometryWithinTwoPercent) {
  DriveSession s("car.urdf.xacro", "car_bicycle.yaml", "bicycle_steering_controller", "reference", "odometry",
                 {"steering:=bicycle"});
  circle_lap(s, [&] {
    EXPECT_NEAR(s.position("front_middle_steering_joint"), s.position("virtual_steering_joint"), 1e-3)
        << "the knuckle mimics the virtual steering joint";
    return s.position("virtual_steering_joint");
  });
}

// The Ackermann car with its traction wheels behind a velocity pid_controller (chaining): the drive writes the PID's
// references, the PID commands the wheels; a quarter of the 2 m circle, odometry against ground truth within 2 % of
// the path.
TEST(Drives, AnAckermannCarChainedIntoTractionPidsFollowsItsOdometry) {
  MobileSession s(mobile("car.urdf.xacro"), mobile("car_ackermann_pids.yaml"),
                  {"joint_state_broadcaster", "traction_pids", "ackermann_steering_controller"},
                  "ackermann_steering_controller/reference", "ackermann_steering_controller/odometry");
  ASSERT_NO_FATAL_FAILURE(s.start());
  ASSERT_NO_FATAL_FAILURE(s.idle(50));
  const Pose2 odom0 = s.odometry(), truth0 = s.truth();
  const double v = 0.5, r = 2.0, quarter = M_PI * r / 2;
  ASSERT_NO_FATAL_FAILURE(s.drive(v, 0, v / r, quarter / v));
  ASSERT_NO_FATAL_FAILURE(s.idle(100));
  const Pose2 t = relative(truth0, s.truth()), o = relative(odom0, s.odometry());
  const double gap = std::hypot(t.x - o.x, t.y - o.y);
  std::printf("chained car: odometry (%.4f, %.4f, %.4f rad), ground truth (%.4f, %.4f, %.4f rad): %.4f m apart\n",
              o.x, o.y, o.yaw, t.x, t.y, t.yaw, gap);
  EXPECT_NEAR(o.yaw, M_PI / 2, 0.05 * M_PI / 2) << s.output();
  EXPECT_LT(gap, 0.02 * quarter) << "ground truth within 2 % of the path";
}

// A 1 m square steered by the drive's own odometry, as a navigation stack would: each leg at its speed, slowing
// down in proportion to what its odometry says is left (the last 15 cm, or 0.3 rad), until it says the leg is done.
// The ground truth's corners against the commanded square (within 3 % of the path).
struct SquareLeg {
  double vx, vy, wz;  // in the body frame
  Pose2 goal;         // in the start frame
};

void square(DriveSession& s, const std::vector<SquareLeg>& legs, double path, bool holonomic) {
  ASSERT_NO_FATAL_FAILURE(s.start());
  ASSERT_NO_FATAL_FAILURE(s.idle(50));
  const Pose2 odom0 = s.odometry(), truth0 = s.truth();
  double worst = 0, worst_heading = 0;
  for (const SquareLeg& leg : legs) {
    const bool turning = leg.wz != 0;
    const double yaw0 = relative(truth0, s.truth()).yaw;
    for (int k = 0; k < 600; ++k) {  // 30 s at most
      const Pose2 o = relative(odom0, s.odometry());
      double scale = 0;
      if (turning) {
        const double left = std::remainder(leg.goal.yaw - o.yaw, 2 * M_PI) * (leg.wz > 0 ? 1 : -1);
        scale = std::clamp(left / 0.3, 0.0, 1.0);
        if (left < 0.003) break;
      } else {  // the distance left along the leg's direction in the start frame
        const double speed = std::hypot(leg.vx, leg.vy), c = std::cos(o.yaw), sn = std::sin(o.yaw);
        const double dx = (c * leg.vx - sn * leg.vy) / speed, dy = (sn * leg.vx + c * leg.vy) / speed;
        const double left = (leg.goal.x - o.x) * dx + (leg.goal.y - o.y) * dy;
        scale = std::clamp(left / 0.15, 0.0, 1.0);
        if (left < 0.002) break;
      }
      scale = std::max(scale, 0.1);
      ASSERT_NO_FATAL_FAILURE(s.drive(leg.vx * scale, leg.vy * scale, leg.wz * scale, s.twist_period(), {}, false));
    }
    ASSERT_NO_FATAL_FAILURE(s.drive(0, 0, 0, 0));
    ASSERT_NO_FATAL_FAILURE(s.idle(60));
    const Pose2 t = relative(truth0, s.truth()), o = relative(odom0, s.odometry());
    const double error = std::hypot(t.x - leg.goal.x, t.y - leg.goal.y);
    if (!turning && holonomic) worst_heading = std::max(worst_heading, angle_between(t.yaw, yaw0));
    std::printf("leg (%g, %g, %g): ground truth (%.4f, %.4f, %.4f rad), odometry (%.4f, %.4f, %.4f rad), goal "
                "(%.3f, %.3f, %.3f rad): %.4f m off\n",
                leg.vx, leg.vy, leg.wz, t.x, t.y, t.yaw, o.x, o.y, o.yaw, leg.goal.x, leg.goal.y, leg.goal.yaw, error);
    worst = std::max(worst, error);
    EXPECT_LT(angle_between(t.yaw, leg.goal.yaw), 0.03 * 2 * M_PI) << "heading after the leg within 3 % of a turn";
  }
  std::printf("worst corner %.4f m (%.2f %% of the %.1f m path); heading drift on straight legs at most %.3f deg\n",
              worst, 100 * worst / path, path, worst_heading * 180 / M_PI);
  EXPECT_LT(worst, 0.03 * path) << "ground truth within 3 % of the commanded path";
  if (holonomic) {
    EXPECT_LT(worst_heading, 2 * M_PI / 180) << "a holonomic base keeps its heading as it goes";
  }
}

TEST(Drives, ATricycleDrivesASquareTurningOnTheSpotWithinThreePercent) {
  DriveSession s("tricycle.urdf.xacro", "tricycle_controllers.yaml", "tricycle_controller", "cmd_vel", "odom");
  std::vector<SquareLeg> legs;
  const double corners[4][2] = {{1, 0}, {1, 1}, {0, 1}, {0, 0}};
  for (int k = 0; k < 4; ++k) {
    legs.push_back({0.3, 0, 0, {corners[k][0], corners[k][1], k * M_PI / 2}});
    legs.push_back({0, 0, 0.6, {corners[k][0], corners[k][1], (k + 1) * M_PI / 2}});
  }
  square(s, legs, 4.0, false);
}

// Forward, left, back and right without turning, then a quarter turn on the spot.
std::vector<SquareLeg> holonomic_square() {
  return {{0.3, 0, 0, {1, 0, 0}},
          {0, 0.3, 0, {1, 1, 0}},
          {-0.3, 0, 0, {0, 1, 0}},
          {0, -0.3, 0, {0, 0, 0}},
          {0, 0, 0.8, {0, 0, M_PI / 2}}};
}

TEST(Drives, AMecanumBaseDrivesASquareSidewaysWithoutTurningThenTurns) {
  DriveSession s("mecanum.urdf.xacro", "mecanum_controllers.yaml", "mecanum_drive_controller", "reference",
                 "odometry");
  square(s, holonomic_square(), 4.0, true);
}

TEST(Drives, AnOmniBaseDrivesASquareSidewaysWithoutTurningThenTurns) {
  DriveSession s("omni.urdf.xacro", "omni_controllers.yaml", "omni_wheel_drive_controller", "cmd_vel", "odom");
  square(s, holonomic_square(), 4.0, true);
}

// Roll and pitch of a pose's orientation (w, x, y, z).
void roll_pitch(const odometry_t& m, double& roll, double& pitch) {
  const double w = m.orientation.w, x = m.orientation.x, y = m.orientation.y, z = m.orientation.z;
  roll = std::atan2(2 * (w * x + y * z), 1 - 2 * (x * x + y * y));
  pitch = std::asin(std::clamp(2 * (w * y - z * x), -1.0, 1.0));
}

TEST(Drives, ABaseWithAZUpColladaBumperAndSprungWheelDropsRestsLevelAndDrivesAMetre) {
  DriveSession s("bumper_bot.urdf.xacro", "bumper_bot_controllers.yaml", "diff_drive_controller", "cmd_vel", "odom");
  ASSERT_NO_FATAL_FAILURE(s.start());
  ASSERT_NO_FATAL_FAILURE(s.idle(200));  // 2 s
  double roll = 0, pitch = 0;
  roll_pitch(s.truth_message(), roll, pitch);
  const double z = s.truth_message().position.z;
  std::printf("at rest after 2 s: base_footprint at z %.5f m, roll %.5f, pitch %.5f rad\n", z, roll, pitch);
  EXPECT_LT(std::abs(roll), 0.01);
  EXPECT_LT(std::abs(pitch), 0.01);
  EXPECT_NEAR(z, 0.0, 0.002) << "on its casters and sprung wheels, base_link on the floor";
  const Pose2 odom0 = s.odometry(), truth0 = s.truth();
  ASSERT_NO_FATAL_FAILURE(s.drive(0.2, 0, 0, 20, [&] { return relative(odom0, s.odometry()).x >= 1.0; }));
  ASSERT_NO_FATAL_FAILURE(s.idle(100));
  const Pose2 t = relative(truth0, s.truth()), o = relative(odom0, s.odometry());
  const double gap = std::hypot(t.x - o.x, t.y - o.y);
  std::printf("drove: odometry (%.4f, %.4f), ground truth (%.4f, %.4f): %.4f m apart\n", o.x, o.y, t.x, t.y, gap);
  EXPECT_NEAR(o.x, 1.0, 0.05) << "stopped once its odometry said 1 m";
  EXPECT_LT(gap, 0.02 * std::hypot(o.x, o.y)) << "ground truth within 2 % of odometry";
}

}  // namespace
}  // namespace lcm_control::testing
