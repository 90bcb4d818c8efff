// diff_drive_controller/DiffDriveController, as ros_controllers' (ROS 1): takes
// a twist_t on `<controller>/cmd_vel`, limits it (linear/x and angular/z:
// velocity and acceleration), turns it into wheel velocities on
// VelocityJointInterface, stops the wheels when no command came for
// cmd_vel_timeout, and dead-reckons the base from the wheel positions (exact
// arcs), publishing odometry_t on `<controller>/odom` at publish_rate and,
// with publish_cmd, the limited twist on `<controller>/cmd_vel_out` every update.
// wheel_radius and wheel_separation default to the URDF's (the wheel link's
// collision cylinder or sphere, and the wheel joints' distance apart).
// ROS 2's parameters (left_wheel_names, right_wheel_names, and limits that hold
// once a max_*/min_* is given, without has_*_limits) are read too.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "controllers/factories.hpp"
#include "controllers/mobile_base.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"

namespace lcm_control::cm {

namespace {

// linear/x or angular/z of ros_controllers' SpeedLimiter (jerk limits are not supported).
struct SpeedLimits {
  bool has_velocity = false, has_acceleration = false;
  double min_velocity = 0, max_velocity = 0, min_acceleration = 0, max_acceleration = 0;

  // v_prev: the limited command of the previous cycle.
  double limit(double v, double v_prev, double dt) const {
    if (has_acceleration && dt > 0) v = std::clamp(v, v_prev + min_acceleration * dt, v_prev + max_acceleration * dt);
    if (has_velocity) v = std::clamp(v, min_velocity, max_velocity);
    return v;
  }
};

// ros2: a limit given (max_* or min_*) holds without has_*_limits, as in ROS 2 since Jazzy.
SpeedLimits read_limits(const Params& p, const char* group, const char* axis, bool ros2) {
  SpeedLimits l;
  const YAML::Node n = p.node(group);
  if (!n) return l;
  const std::string where = fmt::format("{}/{}/{}", p.where(), group, axis);
  const YAML::Node a = n.IsMap() ? n[axis] : YAML::Node();
  if (!a) return l;
  if (!a.IsMap()) throw ControllerError(where + ": expected a map (has_velocity_limits, max_velocity, ...)");
  auto num = [&](const char* key, double fallback) {
    if (!a[key]) return fallback;
    try {
      const double v = a[key].as<double>();
      if (!std::isfinite(v)) throw YAML::Exception({}, "");
      return v;
    } catch (const YAML::Exception&) {
      throw ControllerError(fmt::format("{}/{}: '{}' is not a number", where, key, a[key].Scalar()));
    }
  };
  auto flag = [&](const char* key, const char* max_key, const char* min_key) {
    if (ros2 && !a[key]) return a[max_key] || a[min_key];
    try {
      return a[key] && a[key].as<bool>();
    } catch (const YAML::Exception&) {
      throw ControllerError(fmt::format("{}/{}: '{}' is not true or false", where, key, a[key].Scalar()));
    }
  };
  l.has_velocity = flag("has_velocity_limits", "max_velocity", "min_velocity");
  l.has_acceleration = flag("has_acceleration_limits", "max_acceleration", "min_acceleration");
  l.max_velocity = num("max_velocity", 0);
  l.min_velocity = num("min_velocity", -l.max_velocity);
  l.max_acceleration = num("max_acceleration", 0);
  l.min_acceleration = num("min_acceleration", -l.max_acceleration);
  if (l.has_velocity && !(l.min_velocity <= l.max_velocity))
    throw ControllerError(where + ": min_velocity must be <= max_velocity");
  if (l.has_acceleration && !(l.min_acceleration <= 0 && l.max_acceleration >= 0))
    throw ControllerError(where + ": max_acceleration must be >= 0 and min_acceleration <= 0");
  return l;
}

// The radius of a wheel link's collision cylinder or sphere, 0 if it has neither.
double wheel_radius_of(const RobotModel& model, const std::string& joint) {
  const Joint* j = model.joint(joint);
  const Link* l = j ? model.link(j->child_link) : nullptr;
  if (!l) return 0;
  for (const Geometry& g : l->collisions)
    if (g.type == Geometry::Type::Cylinder || g.type == Geometry::Type::Sphere) return g.radius;
  return 0;
}

class DiffDriveController : public DriveController {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    auto wheels = [&](const char* key) {
      const YAML::Node n = p.node(key);
      if (n && n.IsScalar()) return std::vector<std::string>{p.string(key)};
      return p.strings(key);
    };
    const bool ros2 = p.has("left_wheel_names") || p.has("right_wheel_names");
    for (const auto& n : wheels(ros2 ? "left_wheel_names" : "left_wheel")) left_.push_back(ctx.claim(n, Interface::Velocity));
    for (const auto& n : wheels(ros2 ? "right_wheel_names" : "right_wheel"))
      right_.push_back(ctx.claim(n, Interface::Velocity));
    const RobotModel& m = ctx.model();
    double radius = p.has("wheel_radius") ? p.number("wheel_radius") : wheel_radius_of(m, left_[0]->hardware().name);
    double separation = 0;
    if (p.has("wheel_separation")) {
      separation = p.number("wheel_separation");
    } else {
      const Joint* l = m.joint(left_[0]->hardware().name);  // a chained wheel PID's reference: its joint
      const Joint* r = m.joint(right_[0]->hardware().name);
      separation = (l->origin.translation() - r->origin.translation()).norm();
      ctx.notes.push_back(fmt::format("{}: wheel_separation {:g} m from the URDF ('{}' to '{}')", p.where(), separation,
                                      l->name, r->name));
    }
    if (!(radius > 0))
      throw p.error("wheel_radius", fmt::format("give it: '{}' has no collision cylinder or sphere to take it from",
                                                left_[0]->name));
    if (!(separation > 0)) throw p.error("wheel_separation", fmt::format("{} m: must be > 0", separation));
    separation *= p.number("wheel_separation_multiplier", 1.0);
    radius *= p.number("wheel_radius_multiplier", 1.0);
    left_radius_ = radius * p.number("left_wheel_radius_multiplier", 1.0);
    right_radius_ = radius * p.number("right_wheel_radius_multiplier", 1.0);
    separation_ = separation;
    rate_ = p.number("publish_rate", 50.0);
    if (!(rate_ > 0)) throw p.error("publish_rate", fmt::format("{} Hz: must be > 0", rate_));
    timeout_ = p.number("cmd_vel_timeout", 0.5);
    open_loop_ = p.boolean("open_loop", false);
    position_feedback_ = p.boolean("position_feedback", true);
    const size_t window = static_cast<size_t>(std::max(1.0, p.number("velocity_rolling_window_size", 10)));
    linear_mean_ = angular_mean_ = RollingMean(window);
    linear_ = read_limits(p, "linear", "x", ros2);
    angular_ = read_limits(p, "angular", "z", ros2);
    const std::string odom_frame = p.has("odom_frame_id") ? p.string("odom_frame_id") : "odom";
    const std::string base_frame = p.has("base_frame_id") ? p.string("base_frame_id") : "base_link";
    // ROS 1's publish_cmd, ROS 2's publish_limited_velocity: the twist after the limits, on <name>/cmd_vel_out.
    // The parameters ROS has and this controller does not read are named by the manager when given.
    const char* publish_key = p.has("publish_limited_velocity") ? "publish_limited_velocity" : "publish_cmd";
    if (p.boolean(publish_key, false)) cmd_out_pub_ = ctx.endpoints().publisher<twist_t>(ctx.channel("cmd_vel_out"));
    const std::string name = ctx.name();
    auto bad = [this, name](const std::string& why) {
      if (dropped_++ % 100 == 0) spdlog::warn("{}: dropped a cmd_vel: {} ({} dropped so far)", name, why, dropped_);
    };
    ctx.endpoints().subscribe<twist_t>(
        ctx.channel("cmd_vel"),
        [this, bad](const twist_t& t) {
          if (!std::isfinite(t.linear.x) || !std::isfinite(t.angular.z)) return bad("NaN or Inf");
          if (!running_) return;
          cmd_v_ = t.linear.x;
          cmd_w_ = t.angular.z;
          cmd_new_ = true;
        },
        bad);
    odom_out_.init(ctx, "odom", odom_frame, base_frame);
  }

  void starting(const Time& now) override {
    cmd_v_ = cmd_w_ = last_v_ = last_w_ = 0;
    cmd_new_ = false;
    cmd_time_ = now.seconds();
    brake();
    seed_wheels();
    last_publish_ = now.seconds() - 1.001 / rate_;
    last_update_ = now.seconds();
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_update_ = t;
    if (cmd_new_) {
      cmd_new_ = false;
      cmd_time_ = t;
    }
    double v = cmd_v_, w = cmd_w_;
    if (t - cmd_time_ > timeout_) v = w = 0;
    v = linear_.limit(v, last_v_, period);
    w = angular_.limit(w, last_w_, period);
    last_v_ = v;
    last_w_ = w;
    integrate(v, w, period);
    const double left = (v - w * separation_ / 2) / left_radius_, right = (v + w * separation_ / 2) / right_radius_;
    for (JointData* j : left_) j->command = left;
    for (JointData* j : right_) j->command = right;
    if (cmd_out_pub_.valid()) {
      cmd_out_.utime = now.utime;
      cmd_out_.linear.x = v;
      cmd_out_.angular.z = w;
      cmd_out_pub_.publish(cmd_out_);
    }
    publish(now);
  }

  void stopping(const Time&) override { brake(); }

 private:
  // The mean of the wheels' `field` (JointData::position or ::velocity).
  static double mean(const std::vector<JointData*>& js, double JointData::*field) {
    double s = 0;
    for (const JointData* j : js) s += j->*field;
    return s / static_cast<double>(js.size());
  }
  void brake() {
    for (JointData* j : left_) j->command = 0;
    for (JointData* j : right_) j->command = 0;
  }
  void seed_wheels() {
    left_prev_ = mean(left_, &JointData::position);
    right_prev_ = mean(right_, &JointData::position);
    linear_mean_.clear();
    angular_mean_.clear();
  }

  // Dead reckoning over one period: from the wheels' positions (position_feedback) or velocities, or, open_loop,
  // from the command.
  void integrate(double v_cmd, double w_cmd, double period) {
    double ds = v_cmd * period, dth = w_cmd * period;
    if (!open_loop_) {
      const double l = mean(left_, &JointData::position), r = mean(right_, &JointData::position);
      double dl = (l - left_prev_) * left_radius_, dr = (r - right_prev_) * right_radius_;
      left_prev_ = l;
      right_prev_ = r;
      if (!position_feedback_) {
        dl = mean(left_, &JointData::velocity) * period * left_radius_;
        dr = mean(right_, &JointData::velocity) * period * right_radius_;
      }
      ds = (dl + dr) / 2;
      dth = (dr - dl) / separation_;
    }
    odometry_.move(ds, 0, dth);
    if (period > 0) {
      linear_mean_.add(ds / period);
      angular_mean_.add(dth / period);
    }
  }

  void publish(const Time& now) {
    const double t = now.seconds(), dt = 1.0 / rate_;
    if (t < last_publish_) last_publish_ = t - 1.001 * dt;
    if (!(last_publish_ + dt < t)) return;
    last_publish_ += dt;
    if (t - last_publish_ > dt) last_publish_ = t;
    odom_out_.publish(now.utime, odometry_, linear_mean_.mean(), 0, angular_mean_.mean());
  }

  std::vector<JointData*> left_, right_;
  double left_radius_ = 0, right_radius_ = 0, separation_ = 0, rate_ = 50, timeout_ = 0.5;
  bool open_loop_ = false, position_feedback_ = true;
  SpeedLimits linear_, angular_;
  double cmd_v_ = 0, cmd_w_ = 0, cmd_time_ = 0, last_v_ = 0, last_w_ = 0;
  bool cmd_new_ = false;
  double left_prev_ = 0, right_prev_ = 0;
  double last_publish_ = 0;
  RollingMean linear_mean_, angular_mean_;  // (v, w) of the last velocity_rolling_window_size periods
  OdometryOut odom_out_;
  twist_t cmd_out_{};
  Publisher<twist_t> cmd_out_pub_;  // publish_cmd: the limited twist on <name>/cmd_vel_out
};

}  // namespace

ControllerType diff_drive_controller() {
  ControllerTypeInfo t;
  t.name = "diff_drive_controller/DiffDriveController";
  t.ros = RosVersion::Both;
  t.doc = "a twist_t on <name>/cmd_vel to wheel velocities; odometry_t on <name>/odom (and, publish_cmd, the limited "
          "twist_t on <name>/cmd_vel_out)";
  t.claims = {Interface::Velocity, {"left_wheel", "right_wheel", "left_wheel_names", "right_wheel_names"}, "", {}};
  t.command = {"twist_t", "cmd_vel", 0, ""};
  auto ignored = [](const char* name, const char* type, bool ros1 = true, bool ros2 = false) {
    return ParameterInfo{name, type, "", ros1 ? name : "", ros2 ? name : "", "not implemented (named when given)",
                         false};
  };
  t.parameters = {
      {"left_wheel", "strings", "", "left_wheel", "left_wheel_names", "the left wheel joint(s): a name or a list"},
      {"right_wheel", "strings", "", "right_wheel", "right_wheel_names", "the right wheel joint(s): a name or a list"},
      {"wheel_separation", "number", "", "wheel_separation", "wheel_separation",
       "m (default: the wheel joints' distance apart in the URDF)"},
      {"wheel_radius", "number", "", "wheel_radius", "wheel_radius",
       "m (default: the left wheel's collision cylinder or sphere)"},
      {"wheel_separation_multiplier", "number", "1", "wheel_separation_multiplier", "wheel_separation_multiplier",
       "times wheel_separation"},
      {"wheel_radius_multiplier", "number", "1", "wheel_radius_multiplier", "", "times wheel_radius"},
      {"left_wheel_radius_multiplier", "number", "1", "left_wheel_radius_multiplier", "left_wheel_radius_multiplier",
       "times the left wheels' radius"},
      {"right_wheel_radius_multiplier", "number", "1", "right_wheel_radius_multiplier",
       "right_wheel_radius_multiplier", "times the right wheels' radius"},
      {"publish_rate", "number", "50", "publish_rate", "publish_rate", "Hz of <name>/odom"},
      {"cmd_vel_timeout", "number", "0.5", "cmd_vel_timeout", "cmd_vel_timeout", "s without a command: wheels stop"},
      {"base_frame_id", "string", "base_link", "base_frame_id", "base_frame_id", "odometry's child frame"},
      {"odom_frame_id", "string", "odom", "odom_frame_id", "odom_frame_id", "odometry's frame"},
      ignored("enable_odom_tf", "bool", true, true),
      ignored("wheels_per_side", "number", false, true),
      ignored("use_stamped_vel", "bool", false, true),
      ignored("tf_frame_prefix_enable", "bool", false, true),
      ignored("tf_frame_prefix", "string", false, true),
      {"position_feedback", "bool", "true", "", "position_feedback",
       "odometry from the wheels' positions; false: from their velocities"},
      {"open_loop", "bool", "false", "open_loop", "open_loop", "odometry from the commands instead of the wheels"},
      {"velocity_rolling_window_size", "number", "10", "velocity_rolling_window_size", "velocity_rolling_window_size",
       "samples averaged into the odometry's velocity"},
      {"linear", "map", "", "linear", "linear", "x: {has_velocity_limits, max_velocity, ...} of the linear speed"},
      {"angular", "map", "", "angular", "angular", "z: {has_velocity_limits, max_velocity, ...} of the turn rate"},
      ignored("pose_covariance_diagonal", "list", true, true),
      ignored("twist_covariance_diagonal", "list", true, true),
      ignored("allow_multiple_cmd_vel_publishers", "bool"),
      {"publish_cmd", "bool", "false", "publish_cmd", "publish_limited_velocity",
       "publish the twist after the limits on <name>/cmd_vel_out"},
      ignored("publish_wheel_joint_controller_state", "bool"),
      {"estimate_velocity_from_position", "bool", "", "estimate_velocity_from_position", "", "not implemented", false},
  };
  return {t, [](const std::string&) { return std::make_unique<DiffDriveController>(); }};
}

}  // namespace lcm_control::cm
