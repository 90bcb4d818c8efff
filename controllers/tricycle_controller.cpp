// ros2_controllers' tricycle_controller/TricycleController: one wheel that both steers and drives (a tricycle's
// front wheel; the rear wheels trail). A twist_t on `<name>/cmd_vel` (linear.x, angular.z) becomes the steering
// angle atan(w * wheelbase / v) and the wheel speed v / (wheel_radius * cos(angle)) (a turn on the spot: the wheel
// across, at w * wheelbase / wheel_radius), the speed scaled down while the steering is far from its angle, then
// limited (traction: velocity, acceleration, deceleration, jerk, in rad/s; steering: position, velocity,
// acceleration); zero after cmd_vel_timeout ms without a command. Odometry from the wheel's velocity and angle (or,
// open_loop, the command) as odometry_t on `<name>/odom` every update; with publish_ackermann_command the command
// as ackermann_drive_t on `<name>/cmd_ackermann` (speed in rad/s of the wheel, as ROS 2 sends it).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "controllers/factories.hpp"
#include "controllers/mobile_base.hpp"
#include "lcm_control/ackermann_drive_t.hpp"

namespace lcm_control::cm {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kBig = 1000.0;  // tricycle_controller's bound for a maximum left out when its minimum is given

// tricycle_controller's limits are magnitudes, the same both ways; a NaN bound is none, a minimum alone gets a
// maximum of 1000 and a maximum alone a minimum of 0.
struct Range {
  double min = kNaN, max = kNaN;
  bool on() const { return !std::isnan(min) && !std::isnan(max); }
};

// mirror: a position range, whose one end given alone mirrors to the other (SteeringLimiter).
Range range(const Params& p, const char* group, const char* what, const std::string& unit, bool mirror = false) {
  Range r;
  const YAML::Node n = p.node(group);
  if (!n) return r;
  const std::string where = fmt::format("{}/{}", p.where(), group);
  if (!n.IsMap()) throw ControllerError(where + ": expected a map (max_velocity, max_acceleration, ...)");
  auto num = [&](const std::string& key) {
    const YAML::Node v = n[key];
    if (!v) return kNaN;
    try {
      return v.as<double>();
    } catch (const YAML::Exception&) {
      throw ControllerError(fmt::format("{}/{}: '{}' is not a number", where, key, v.Scalar()));
    }
  };
  r.min = num(std::string("min_") + what);
  r.max = num(std::string("max_") + what);
  if (mirror) {
    if (std::isnan(r.max)) r.max = -r.min;
    if (std::isnan(r.min)) r.min = -r.max;
    if (r.on() && r.min > r.max)
      throw ControllerError(fmt::format("{}/min_{} {} is above max_{} {} {}", where, what, r.min, what, r.max, unit));
    return r;
  }
  if (!std::isnan(r.min) && std::isnan(r.max)) r.max = kBig;
  if (!std::isnan(r.max) && std::isnan(r.min)) r.min = 0;
  if (r.on() && (r.min < 0 || r.max < 0 || r.min > r.max))
    throw ControllerError(fmt::format("{}/min_{} {} and max_{} {} {}: give magnitudes, min <= max (the same limit "
                                      "holds both ways)",
                                      where, what, r.min, what, r.max, unit));
  return r;
}

class TricycleController : public DriveController {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    traction_ = claim_named(ctx, "traction_joint_name", p.string("traction_joint_name"), Interface::Velocity);
    steering_ = claim_named(ctx, "steering_joint_name", p.string("steering_joint_name"), Interface::Position);
    auto positive = [&](const char* key, const std::string& what) {
      const double v = p.number(key);
      if (!(v > 0)) throw p.error(key, fmt::format("{} m: must be > 0 ({})", v, what));
      return v;
    };
    wheelbase_ = positive("wheelbase", fmt::format("from the rear axle to '{}'", steering_->name));
    radius_ = positive("wheel_radius", fmt::format("the radius of the wheel '{}' drives", traction_->name));
    open_loop_ = p.boolean("open_loop", false);
    twist_only_ = p.boolean("odom_only_twist", false);
    timeout_ = p.number("cmd_vel_timeout", 500) / 1000.0;  // ms, as ROS 2 gives it
    if (!(timeout_ >= 0)) throw p.error("cmd_vel_timeout", "must be >= 0 (milliseconds)");
    const double window = p.number("velocity_rolling_window_size", 10);
    if (!(window >= 1)) throw p.error("velocity_rolling_window_size", fmt::format("{}: must be >= 1", window));
    linear_mean_ = angular_mean_ = RollingMean(size_t(window));
    speed_ = range(p, "traction", "velocity", "rad/s");
    acceleration_ = range(p, "traction", "acceleration", "rad/s^2");
    deceleration_ = range(p, "traction", "deceleration", "rad/s^2");
    jerk_ = range(p, "traction", "jerk", "rad/s^3");
    steer_range_ = range(p, "steering", "position", "rad", true);
    steer_rate_ = range(p, "steering", "velocity", "rad/s");
    steer_acceleration_ = range(p, "steering", "acceleration", "rad/s^2");
    take_twists(ctx, cmd_vel_, "cmd_vel");
    publish_odometry(ctx, odometry_out_, "odom");
    if (p.boolean("publish_ackermann_command", false))
      ackermann_pub_ = ctx.endpoints().publisher<ackermann_drive_t>(ctx.channel("cmd_ackermann"));
  }

  void starting(const Time& now) override {
    cmd_vel_.clear();
    traction_->command = 0;
    steering_->command = steering_->position;
    for (auto& c : previous_) c = {0, 0};
    linear_mean_.clear();
    angular_mean_.clear();
    linear_ = angular_ = 0;
    last_update_ = now.seconds();
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_update_ = t;
    cmd_vel_.take(t);
    double v = 0, w = 0;
    if (cmd_vel_.any() && cmd_vel_.age(t) <= timeout_) {
      v = cmd_vel_.vx();
      w = cmd_vel_.wz();
    }
    const double ws_read = traction_->velocity, alpha_read = steering_->position;
    if (open_loop_) {
      linear_ = v;
      angular_ = w;
      odometry_.move(v * period, 0, w * period);
    } else if (std::isfinite(ws_read) && std::isfinite(alpha_read)) {
      const double vs = ws_read * radius_, vx = vs * std::cos(alpha_read), wz = vs * std::sin(alpha_read) / wheelbase_;
      odometry_.move(vx * period, 0, wz * period);
      linear_mean_.add(vx);
      angular_mean_.add(wz);
      linear_ = linear_mean_.mean();
      angular_ = angular_mean_.mean();
    }
    odometry_out_.publish(now.utime, odometry_, linear_, 0, angular_, twist_only_);

    // tricycle_controller::twist_to_ackermann, then its scaling and limiters.
    double alpha = 0, ws = 0;
    if (v == 0 && w != 0) {  // a turn on the spot
      alpha = w > 0 ? M_PI_2 : -M_PI_2;
      ws = std::abs(w) * wheelbase_ / radius_;
    } else {
      alpha = (v == 0 || w == 0) ? 0.0 : std::atan(w * wheelbase_ / v);
      ws = v / (radius_ * std::cos(alpha));
    }
    const double delta = std::abs(alpha - alpha_read);
    ws *= delta < M_PI / 6 ? 1.0 : delta > M_PI_2 ? 0.01 : std::cos(delta);
    const Command& last = previous_[1];
    const Command& before = previous_[0];
    ws = limit_traction(ws, last.speed, before.speed, period);
    alpha = limit_steering(alpha, last.angle, before.angle, period);
    previous_[0] = previous_[1];
    previous_[1] = {ws, alpha};
    if (ackermann_pub_.valid()) {
      ackermann_.utime = now.utime;
      ackermann_.speed = ws;
      ackermann_.steering_angle = alpha;
      ackermann_pub_.publish(ackermann_);
    }
    traction_->command = ws;
    steering_->command = alpha;
  }

  void stopping(const Time&) override { traction_->command = 0; }

 private:
  struct Command {
    double speed = 0, angle = 0;
  };

  // TractionLimiter: jerk, then acceleration (deceleration when slowing), then speed, all as magnitudes.
  double limit_traction(double v, double v0, double v1, double dt) const {
    if (jerk_.on()) {
      const double dv = v - v0, dv0 = v0 - v1, dt2 = 2 * dt * dt;
      v = v0 + dv0 + std::copysign(std::clamp(std::abs(dv - dv0), jerk_.min * dt2, jerk_.max * dt2), dv - dv0);
    }
    const Range& a = std::abs(v) >= std::abs(v0) ? acceleration_ : deceleration_;
    if (a.on()) v = v0 + std::copysign(std::clamp(std::abs(v - v0), a.min * dt, a.max * dt), v - v0);
    if (speed_.on()) v = std::copysign(std::clamp(std::abs(v), speed_.min, speed_.max), v);
    return v;
  }

  // SteeringLimiter: acceleration, then rate, then position.
  double limit_steering(double p, double p0, double p1, double dt) const {
    if (steer_acceleration_.on()) {
      const double dv = p - p0, dp0 = p0 - p1, dt2 = 2 * dt * dt;
      p = p0 + dp0 +
          std::copysign(std::clamp(std::abs(dv - dp0), steer_acceleration_.min * dt2, steer_acceleration_.max * dt2),
                        dv - dp0);
    }
    if (steer_rate_.on())
      p = p0 + std::copysign(std::clamp(std::abs(p - p0), steer_rate_.min * dt, steer_rate_.max * dt), p - p0);
    if (steer_range_.on()) p = std::clamp(p, steer_range_.min, steer_range_.max);
    return p;
  }

  JointData* traction_ = nullptr;
  JointData* steering_ = nullptr;
  double wheelbase_ = 0, radius_ = 0, timeout_ = 0.5;
  bool open_loop_ = false, twist_only_ = false;
  Range speed_, acceleration_, deceleration_, jerk_, steer_range_, steer_rate_, steer_acceleration_;
  Command previous_[2];  // the second to last and the last command
  TwistInput cmd_vel_;
  RollingMean linear_mean_, angular_mean_;
  double linear_ = 0, angular_ = 0;
  OdometryOut odometry_out_;
  ackermann_drive_t ackermann_{};
  Publisher<ackermann_drive_t> ackermann_pub_;
};

}  // namespace

ControllerType tricycle_controller() {
  ControllerTypeInfo t;
  t.name = "tricycle_controller/TricycleController";
  t.ros = RosVersion::Ros2;
  t.doc = "a twist_t on <name>/cmd_vel to one wheel's steering angle and speed; odometry_t on <name>/odom";
  t.claims = {Interface::Velocity, {"traction_joint_name"}, "", {}};
  t.claims.also = {{Interface::Position, {"steering_joint_name"}}};
  t.command = {"twist_t", "cmd_vel", 0, ""};
  t.parameters = {
      ros2_parameter("traction_joint_name", "string", "", "the joint that drives the steered wheel (velocity)"),
      ros2_parameter("steering_joint_name", "string", "", "the joint that steers it (position)"),
      ros2_parameter("wheelbase", "number", "", "m from the rear axle to the steered wheel"),
      ros2_parameter("wheel_radius", "number", "", "m, the steered wheel's"),
      ros2_parameter("open_loop", "bool", "false", "odometry from the command instead of the joints"),
      ros2_parameter("odom_only_twist", "bool", "false", "odometry without the pose (its twist only)"),
      ros2_parameter("cmd_vel_timeout", "number", "500", "ms without a command: the wheel stops"),
      ros2_parameter("publish_ackermann_command", "bool", "false",
                     "publish the command as ackermann_drive_t on <name>/cmd_ackermann"),
      ros2_parameter("velocity_rolling_window_size", "number", "10", "samples averaged into the odometry's twist"),
      ros2_parameter("traction", "map", "",
                     "{min,max}_{velocity,acceleration,deceleration,jerk} of the wheel's speed, magnitudes in rad/s"),
      ros2_parameter("steering", "map", "", "{min,max}_{position,velocity,acceleration} of the steering angle, rad"),
  };
  for (ParameterInfo& f : drive_frame_parameters()) t.parameters.push_back(std::move(f));
  return {t, [](const std::string&) { return std::make_unique<TricycleController>(); }};
}

}  // namespace lcm_control::cm
