// ros2_controllers' holonomic bases. mecanum_drive_controller/MecanumDriveController: four mecanum wheels (front
// left, front right, rear right, rear left) from a twist_t on `<name>/reference` (linear.x, linear.y, angular.z),
// held for reference_timeout s (0: the cycle it came in only), each axis through control_toolbox's rate limiter;
// odometry_t on `<name>/odometry` from the wheels' velocities. omni_wheel_drive_controller/OmniWheelDriveController:
// three or more omni wheels evenly spaced on a circle of robot_radius, the first at wheel_offset from the x axis and
// the rest anti-clockwise, from a twist_t on `<name>/cmd_vel` held for cmd_vel_timeout s; odometry_t on
// `<name>/odom` from the wheels' positions (or velocities, or open_loop the command) by least squares. Wheel
// velocities in rad/s on the velocity interface, positive rolling the wheel forward along its own rolling direction.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "controllers/factories.hpp"
#include "controllers/mobile_base.hpp"

namespace lcm_control::cm {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double nested_number(const Params& p, const char* group, const std::vector<const char*>& path, double fallback) {
  YAML::Node n = p.node(group);
  std::string where = fmt::format("{}/{}", p.where(), group);
  for (const char* k : path) {
    if (!n || !n.IsMap()) return fallback;
    n.reset(n[k]);  // not n = n[k], which would write the child into the parameters
    where += std::string("/") + k;
  }
  if (!n) return fallback;
  try {
    return n.as<double>();
  } catch (const YAML::Exception&) {
    throw ControllerError(fmt::format("{}: '{}' is not a number", where, n.Scalar()));
  }
}

// The mecanum drive's linear.x, linear.y or angular.z limits, as control_toolbox's RateLimiter takes them.
RateLimiter axis_limits(const Params& p, const char* group, const char* axis) {
  auto num = [&](const char* key) { return nested_number(p, group, {axis, key}, kNaN); };
  RateLimiter::Bounds b;
  b.min_value = num("min_velocity");
  b.max_value = num("max_velocity");
  b.min_rate_negative = num("max_acceleration_reverse");
  b.max_rate_positive = num("max_acceleration");
  b.min_rate_positive = num("max_deceleration");
  b.max_rate_negative = num("max_deceleration_reverse");
  b.min_second = num("min_jerk");
  b.max_second = num("max_jerk");
  try {
    return RateLimiter(b);
  } catch (const std::invalid_argument& e) {
    throw ControllerError(fmt::format("{}/{}/{}: {}", p.where(), group, axis, e.what()));
  }
}

class MecanumDriveController : public DriveController {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    static const char* kWheels[4] = {"front_left", "front_right", "rear_right", "rear_left"};
    for (int i = 0; i < 4; ++i) {
      const std::string key = fmt::format("{}_wheel_command_joint_name", kWheels[i]);
      wheels_[i] = claim_named(ctx, key, p.string(key), Interface::Velocity);
      state_[i] = wheels_[i];
      const std::string state_key = fmt::format("{}_wheel_state_joint_name", kWheels[i]);
      if (p.has(state_key) && !p.node(state_key).Scalar().empty()) state_[i] = ctx.read(p.string(state_key), state_key);
    }
    radius_ = nested_number(p, "kinematics", {"wheels_radius"}, kNaN);
    if (!(radius_ > 0))
      throw p.error("kinematics/wheels_radius",
                    fmt::format("{} m: must be > 0 (the radius of the wheels '{}', ...)", radius_, wheels_[0]->name));
    lxy_ = nested_number(p, "kinematics", {"sum_of_robot_center_projection_on_X_Y_axis"}, 0.0);
    if (!(lxy_ > 0))
      throw p.error("kinematics/sum_of_robot_center_projection_on_X_Y_axis",
                    fmt::format("{} m: must be > 0 (lx + ly: the wheels' distance from the centre along x plus along "
                                "y)",
                                lxy_));
    offset_x_ = nested_number(p, "kinematics", {"base_frame_offset", "x"}, 0.0);
    offset_y_ = nested_number(p, "kinematics", {"base_frame_offset", "y"}, 0.0);
    offset_theta_ = nested_number(p, "kinematics", {"base_frame_offset", "theta"}, 0.0);
    timeout_ = p.number("reference_timeout", 0.0);
    if (!(timeout_ >= 0)) throw p.error("reference_timeout", fmt::format("{} s: must be >= 0", timeout_));
    limits_[0] = axis_limits(p, "linear", "x");
    limits_[1] = axis_limits(p, "linear", "y");
    limits_[2] = axis_limits(p, "angular", "z");
    take_twists(ctx, reference_, "reference");
    publish_odometry(ctx, odometry_out_, "odometry");
  }

  void starting(const Time& now) override {
    reference_.clear();
    for (JointData* j : wheels_) j->command = 0;
    for (auto& c : previous_) c[0] = c[1] = c[2] = 0;
    last_update_ = now.seconds();
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_update_ = t;
    reference_.take(t);
    // Odometry: the body twist at the wheels' centre from their speeds, moved to the base frame.
    const double fl = state_[0]->velocity, fr = state_[1]->velocity, rr = state_[2]->velocity,
                 rl = state_[3]->velocity;
    double vx = 0, vy = 0, wz = 0;
    if (std::isfinite(fl + fr + rr + rl) && period >= 1e-4) {
      const double cx = radius_ / 4 * (fl + rl + rr + fr), cy = radius_ / 4 * (-fl + rl - rr + fr);
      wz = radius_ / (4 * lxy_) * (-fl - rl + rr + fr);
      const double c = std::cos(-offset_theta_), s = std::sin(-offset_theta_);
      const double bx = c * cx - s * cy, by = s * cx + c * cy;
      const double ox = c * -offset_x_ - s * -offset_y_, oy = s * -offset_x_ + c * -offset_y_;
      vx = bx + oy * wz;
      vy = by - ox * wz;
      odometry_.move(vx * period, vy * period, wz * period);
    }
    if (reference_.any() && reference_.age(t) <= timeout_) {  // timeout 0: the cycle it came in only
      double cmd[3] = {reference_.vx(), reference_.vy(), reference_.wz()};
      for (int a = 0; a < 3; ++a) {
        cmd[a] = limits_[a].limit(cmd[a], previous_[1][a], previous_[0][a], period);
        previous_[0][a] = previous_[1][a];
        previous_[1][a] = cmd[a];
      }
      // The twist at the wheels' centre, from the base frame's.
      const double c = std::cos(offset_theta_), s = std::sin(offset_theta_);
      const double x = c * cmd[0] - s * cmd[1] + offset_y_ * cmd[2];
      const double y = s * cmd[0] + c * cmd[1] - offset_x_ * cmd[2];
      const double w = cmd[2];
      wheels_[0]->command = (x - y - lxy_ * w) / radius_;  // front left
      wheels_[1]->command = (x + y + lxy_ * w) / radius_;  // front right
      wheels_[2]->command = (x - y + lxy_ * w) / radius_;  // rear right
      wheels_[3]->command = (x + y - lxy_ * w) / radius_;  // rear left
    } else {
      for (JointData* j : wheels_) j->command = 0;
    }
    odometry_out_.publish(now.utime, odometry_, vx, vy, wz);
  }

  void stopping(const Time&) override {
    for (JointData* j : wheels_) j->command = 0;
  }

 private:
  JointData* wheels_[4] = {};
  const JointData* state_[4] = {};
  double radius_ = 0, lxy_ = 0, offset_x_ = 0, offset_y_ = 0, offset_theta_ = 0, timeout_ = 0;
  RateLimiter limits_[3];
  double previous_[2][3] = {};  // the second to last and the last limited command: x, y, z
  TwistInput reference_;
  OdometryOut odometry_out_;
};

class OmniWheelDriveController : public DriveController {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const std::vector<std::string> names = p.strings("wheel_names");
    if (names.size() < 3)
      throw p.error("wheel_names", fmt::format("{} wheel(s): an omni base needs three or more, evenly spaced",
                                               names.size()));
    for (const auto& n : names) wheels_.push_back(claim_named(ctx, "wheel_names", n, Interface::Velocity));
    const double offset = p.number("wheel_offset", 0.0);
    robot_radius_ = p.number("robot_radius");
    if (!(robot_radius_ > 0))
      throw p.error("robot_radius", fmt::format("{} m: must be > 0 (the wheels' distance from the centre)",
                                                robot_radius_));
    wheel_radius_ = p.number("wheel_radius");
    if (!(wheel_radius_ > 0))
      throw p.error("wheel_radius", fmt::format("{} m: must be > 0 (the radius of the wheels '{}', ...)",
                                                wheel_radius_, names[0]));
    open_loop_ = p.boolean("open_loop", false);
    position_feedback_ = p.boolean("position_feedback", true);
    timeout_ = p.number("cmd_vel_timeout", 0.5);
    if (!(timeout_ >= 0)) throw p.error("cmd_vel_timeout", fmt::format("{} s: must be >= 0", timeout_));
    const size_t n = wheels_.size();
    // Wheel i at angle theta_i: its speed times its radius is sin(theta_i) vx - cos(theta_i) vy - robot_radius wz.
    Eigen::MatrixXd a(n, 3);
    for (size_t i = 0; i < n; ++i) {
      const double theta = 2 * M_PI / double(n) * double(i) + offset;
      a(Eigen::Index(i), 0) = std::sin(theta);
      a(Eigen::Index(i), 1) = -std::cos(theta);
      a(Eigen::Index(i), 2) = -robot_radius_;
    }
    inverse_ = a;
    forward_ = a.completeOrthogonalDecomposition().pseudoInverse() * wheel_radius_;  // wheel speeds -> twist
    speeds_.assign(n, 0.0);
    old_position_.assign(n, 0.0);
    take_twists(ctx, cmd_vel_, "cmd_vel");
    publish_odometry(ctx, odometry_out_, "odom");
  }

  void starting(const Time& now) override {
    cmd_vel_.clear();
    for (size_t i = 0; i < wheels_.size(); ++i) {
      wheels_[i]->command = 0;
      old_position_[i] = wheels_[i]->position;
    }
    last_update_ = now.seconds();
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_update_ = t;
    cmd_vel_.take(t);
    double vx = 0, vy = 0, wz = 0;
    if (cmd_vel_.any() && cmd_vel_.age(t) <= timeout_) {
      vx = cmd_vel_.vx();
      vy = cmd_vel_.vy();
      wz = cmd_vel_.wz();
    }
    double ox = vx, oy = vy, ow = wz;
    if (!open_loop_ && period >= 1e-6) {
      for (size_t i = 0; i < wheels_.size(); ++i) {
        const double q = wheels_[i]->position;
        speeds_[i] = position_feedback_ ? (q - old_position_[i]) / period : wheels_[i]->velocity;
        old_position_[i] = q;
      }
      ox = oy = ow = 0;
      for (size_t i = 0; i < wheels_.size(); ++i) {
        ox += forward_(0, Eigen::Index(i)) * speeds_[i];
        oy += forward_(1, Eigen::Index(i)) * speeds_[i];
        ow += forward_(2, Eigen::Index(i)) * speeds_[i];
      }
    }
    if (std::isfinite(ox + oy + ow)) {
      odometry_.move(ox * period, oy * period, ow * period);
      odometry_out_.publish(now.utime, odometry_, ox, oy, ow);
    }
    for (size_t i = 0; i < wheels_.size(); ++i) {
      const Eigen::Index k = Eigen::Index(i);
      wheels_[i]->command = (inverse_(k, 0) * vx + inverse_(k, 1) * vy + inverse_(k, 2) * wz) / wheel_radius_;
    }
  }

  void stopping(const Time&) override {
    for (JointData* j : wheels_) j->command = 0;
  }

 private:
  std::vector<JointData*> wheels_;
  double robot_radius_ = 0, wheel_radius_ = 0, timeout_ = 0.5;
  bool open_loop_ = false, position_feedback_ = true;
  Eigen::MatrixXd inverse_, forward_;  // twist -> wheel rim speeds (n x 3); wheel speeds -> twist (3 x n)
  std::vector<double> speeds_, old_position_;
  TwistInput cmd_vel_;
  OdometryOut odometry_out_;
};

}  // namespace

ControllerType mecanum_drive_controller() {
  ControllerTypeInfo t;
  t.name = "mecanum_drive_controller/MecanumDriveController";
  t.ros = RosVersion::Ros2;
  t.doc = "a twist_t on <name>/reference (x, y, z) to four mecanum wheels' velocities; odometry_t on <name>/odometry";
  t.claims = {Interface::Velocity,
              {"front_left_wheel_command_joint_name", "front_right_wheel_command_joint_name",
               "rear_right_wheel_command_joint_name", "rear_left_wheel_command_joint_name"},
              "",
              {}};
  t.command = {"twist_t", "reference", 0, ""};
  t.parameters = {
      ros2_parameter("front_left_wheel_command_joint_name", "string", "", "the front left wheel's joint"),
      ros2_parameter("front_right_wheel_command_joint_name", "string", "", "the front right wheel's joint"),
      ros2_parameter("rear_right_wheel_command_joint_name", "string", "", "the rear right wheel's joint"),
      ros2_parameter("rear_left_wheel_command_joint_name", "string", "", "the rear left wheel's joint"),
      ros2_parameter("front_left_wheel_state_joint_name", "string", "", "another joint to read its state from"),
      ros2_parameter("front_right_wheel_state_joint_name", "string", "", "another joint to read its state from"),
      ros2_parameter("rear_right_wheel_state_joint_name", "string", "", "another joint to read its state from"),
      ros2_parameter("rear_left_wheel_state_joint_name", "string", "", "another joint to read its state from"),
      ros2_parameter("kinematics", "map", "",
                     "wheels_radius (m), sum_of_robot_center_projection_on_X_Y_axis (lx + ly, m), base_frame_offset "
                     "{x, y, theta}"),
      ros2_parameter("reference_timeout", "number", "0.0",
                     "s a reference holds; then the wheels stop (0: the cycle it came in only)"),
      ros2_parameter("linear", "map", "", "x: and y: limits ({min,max}_velocity, max_acceleration(_reverse), ...)"),
      ros2_parameter("angular", "map", "", "z: limits ({min,max}_velocity, max_acceleration(_reverse), ...)"),
  };
  for (ParameterInfo& f : drive_frame_parameters()) t.parameters.push_back(std::move(f));
  return {t, [](const std::string&) { return std::make_unique<MecanumDriveController>(); }};
}

ControllerType omni_wheel_drive_controller() {
  ControllerTypeInfo t;
  t.name = "omni_wheel_drive_controller/OmniWheelDriveController";
  t.ros = RosVersion::Ros2;
  t.doc = "a twist_t on <name>/cmd_vel (x, y, z) to three or more omni wheels' velocities; odometry_t on <name>/odom";
  t.claims = {Interface::Velocity, {"wheel_names"}, "", {}};
  t.command = {"twist_t", "cmd_vel", 0, ""};
  t.parameters = {
      ros2_parameter("wheel_names", "strings", "",
                     "the wheels' joints, anti-clockwise from the one at wheel_offset from the x axis"),
      ros2_parameter("wheel_offset", "number", "0", "rad from the x axis to the first wheel"),
      ros2_parameter("robot_radius", "number", "", "m from the centre to each wheel"),
      ros2_parameter("wheel_radius", "number", "", "m, the wheels'"),
      ros2_parameter("open_loop", "bool", "false", "odometry from the command instead of the wheels"),
      ros2_parameter("position_feedback", "bool", "true", "odometry from the wheels' positions (else velocities)"),
      ros2_parameter("cmd_vel_timeout", "number", "0.5", "s without a command: the wheels stop"),
      ros2_parameter("diagonal_covariance", "map", "", "no covariances here: not implemented (named when given)", false),
  };
  for (ParameterInfo& f : drive_frame_parameters()) t.parameters.push_back(std::move(f));
  return {t, [](const std::string&) { return std::make_unique<OmniWheelDriveController>(); }};
}

}  // namespace lcm_control::cm
