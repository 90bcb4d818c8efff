#include "controllers/mobile_base.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

namespace lcm_control::cm {

void PlanarOdometry::move(double dx, double dy, double dheading) {
  const double h0 = heading_;
  if (std::abs(dheading) < 1e-6) {
    const double mid = h0 + dheading / 2;
    x_ += dx * std::cos(mid) - dy * std::sin(mid);
    y_ += dx * std::sin(mid) + dy * std::cos(mid);
  } else {
    const double h1 = h0 + dheading;
    const double sin_d = std::sin(h1) - std::sin(h0), cos_d = std::cos(h1) - std::cos(h0);
    x_ += (dx * sin_d + dy * cos_d) / dheading;
    y_ += (-dx * cos_d + dy * sin_d) / dheading;
  }
  heading_ = std::remainder(h0 + dheading, 2 * M_PI);
}

void PlanarOdometry::set(double x, double y, double heading) {
  x_ = x;
  y_ = y;
  heading_ = std::remainder(heading, 2 * M_PI);
}

void RollingMean::add(double v) {
  if (filled_ == ring_.size()) sum_ -= ring_[next_];
  ring_[next_] = v;
  sum_ += v;
  next_ = (next_ + 1) % ring_.size();
  filled_ = std::min(filled_ + 1, ring_.size());
}

void RollingMean::clear() {
  std::fill(ring_.begin(), ring_.end(), 0.0);
  next_ = filled_ = 0;
  sum_ = 0;
}

JointData* claim_named(ControllerContext& ctx, const std::string& key, const std::string& joint, Interface iface) {
  try {
    return ctx.claim(joint, iface);
  } catch (const InterfaceError& e) {
    throw InterfaceError(fmt::format("{}/{}: {}", ctx.params().where(), key, e.what()));
  } catch (const ControllerError& e) {
    throw ControllerError(fmt::format("{}/{}: {}", ctx.params().where(), key, e.what()));
  }
}

void DriveController::take_twists(ControllerContext& ctx, TwistInput& input, const std::string& channel) {
  const std::string name = ctx.name();
  input.subscribe(ctx, channel, [this, name, channel](const std::string& why) {
    if (dropped_++ % 100 == 0)
      spdlog::warn("{}: dropped a twist on {}: {} ({} dropped so far)", name, channel, why, dropped_);
  });
}

void DriveController::publish_odometry(ControllerContext& ctx, OdometryOut& out, const std::string& channel) {
  const Params& p = ctx.params();
  out.init(ctx, channel, p.has("odom_frame_id") ? p.string("odom_frame_id") : "odom",
           p.has("base_frame_id") ? p.string("base_frame_id") : "base_link");
}

std::vector<ParameterInfo> drive_frame_parameters() {
  std::vector<ParameterInfo> p = {ros2_parameter("base_frame_id", "string", "base_link", "odometry's child frame"),
                                  ros2_parameter("odom_frame_id", "string", "odom", "odometry's frame")};
  for (const auto& [name, type] : {std::pair{"enable_odom_tf", "bool"}, {"tf_frame_prefix", "string"},
                                   {"tf_frame_prefix_enable", "bool"}, {"twist_covariance_diagonal", "list"},
                                   {"pose_covariance_diagonal", "list"}})
    p.push_back(ros2_parameter(name, type, "", "no TF or covariances here: not implemented (named when given)", false));
  return p;
}

void TwistInput::subscribe(ControllerContext& ctx, const std::string& channel,
                           std::function<void(const std::string&)> bad) {
  ctx.endpoints().subscribe<twist_t>(
      ctx.channel(channel),
      [this, bad](const twist_t& t) {
        if (!std::isfinite(t.linear.x) || !std::isfinite(t.linear.y) || !std::isfinite(t.angular.z))
          return bad("NaN or Inf");
        vx_ = t.linear.x;
        vy_ = t.linear.y;
        wz_ = t.angular.z;
        fresh_ = true;
      },
      bad);
}

void TwistInput::take(double now_s) {
  if (!fresh_) return;
  fresh_ = false;
  any_ = true;
  arrived_ = now_s;
}

void OdometryOut::init(ControllerContext& ctx, const std::string& channel, const std::string& odom_frame,
                       const std::string& base_frame) {
  msg_.frame_id = odom_frame;
  msg_.child_frame_id = base_frame;
  pub_ = ctx.endpoints().publisher<odometry_t>(ctx.channel(channel));
}

void OdometryOut::publish(int64_t utime, const PlanarOdometry& odom, double vx, double vy, double wz,
                          bool twist_only) {
  msg_.utime = utime;
  if (!twist_only) {
    msg_.position = {odom.x(), odom.y(), 0};
    msg_.orientation = {std::cos(odom.heading() / 2), 0, 0, std::sin(odom.heading() / 2)};
    msg_.yaw = odom.heading();
  }
  msg_.linear = {vx, vy, 0};
  msg_.angular = {0, 0, wz};
  pub_.publish(msg_);
}

RateLimiter::RateLimiter(Bounds b) : b_(b) {
  value_ = !std::isnan(b_.max_value);
  if (std::isnan(b_.min_value)) b_.min_value = -b_.max_value;
  if (value_ && b_.min_value > b_.max_value) throw std::invalid_argument("min_velocity is above max_velocity");
  rate_ = !std::isnan(b_.max_rate_positive);
  if (std::isnan(b_.min_rate_negative)) b_.min_rate_negative = -b_.max_rate_positive;
  if (rate_) {
    if (b_.min_rate_negative > b_.max_rate_positive)
      throw std::invalid_argument("the acceleration bounds contradict each other (reverse above forward)");
    if (std::isnan(b_.max_rate_negative)) b_.max_rate_negative = b_.max_rate_positive;
    if (std::isnan(b_.min_rate_positive)) b_.min_rate_positive = b_.min_rate_negative;
    if (b_.min_rate_positive > b_.max_rate_negative)
      throw std::invalid_argument("the deceleration bounds contradict each other");
  }
  second_ = !std::isnan(b_.max_second);
  if (std::isnan(b_.min_second)) b_.min_second = -b_.max_second;
  if (second_ && b_.min_second > b_.max_second) throw std::invalid_argument("min_jerk is above max_jerk");
}

double RateLimiter::limit(double v, double v0, double v1, double dt) const {
  if (second_) {
    const double dv = v - v0, dv0 = v0 - v1;
    if ((dv - dv0) * (v - v0) > 0) v = v0 + dv0 + std::clamp(dv - dv0, b_.min_second * dt * dt, b_.max_second * dt * dt);
  }
  if (rate_) {
    double lo = b_.min_rate_negative, hi = b_.max_rate_positive;
    if (v0 > 0) lo = b_.min_rate_positive;
    if (v0 < 0) hi = b_.max_rate_negative;
    if (v0 > 0) hi = b_.max_rate_positive;
    if (v0 < 0) lo = b_.min_rate_negative;
    v = v0 + std::clamp(v - v0, lo * dt, hi * dt);
  }
  if (value_) v = std::clamp(v, b_.min_value, b_.max_value);
  return v;
}

}  // namespace lcm_control::cm
