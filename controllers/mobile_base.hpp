// What the drive controllers share (diff drive, steering drives, tricycle, mecanum, omni): the body twist they take
// on a channel, the dead reckoning of the base in the plane, the rolling mean of its velocities, the odometry_t they
// publish, and control_toolbox's rate limiter for their commands. Everything after init() is real-time safe.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "bus/endpoints.hpp"
#include "controller_interface/controller.hpp"
#include "controller_interface/controller_type.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"

namespace lcm_control::cm {

// The base's pose in the frame where it started (or was last set): x, y in m, heading in rad (wrapped to ±pi).
class PlanarOdometry {
 public:
  // One period's motion at a constant body twist: forward dx, leftward dy (m) and turn dheading (rad), integrated
  // exactly (the arc; second-order Runge-Kutta while it hardly turns).
  void move(double dx, double dy, double dheading);
  void set(double x, double y, double heading);
  double x() const { return x_; }
  double y() const { return y_; }
  double heading() const { return heading_; }

 private:
  double x_ = 0, y_ = 0, heading_ = 0;
};

// The mean of the last `size` samples (rcpputils' RollingMeanAccumulator): a ring, sized at construction.
class RollingMean {
 public:
  explicit RollingMean(size_t size = 10) : ring_(size < 1 ? 1 : size, 0.0) {}
  void add(double v);
  double mean() const { return filled_ == 0 ? 0.0 : sum_ / double(filled_); }
  void clear();

 private:
  std::vector<double> ring_;
  size_t next_ = 0, filled_ = 0;
  double sum_ = 0;
};

// A twist_t on `<controller>/<channel>`: the newest one, and when (in hardware time) it arrived. A twist that is not
// finite is dropped and handed to `bad`.
class TwistInput {
 public:
  void subscribe(ControllerContext& ctx, const std::string& channel, std::function<void(const std::string&)> bad);
  // At the start of each update: a twist that came since the last cycle is stamped `now_s`.
  void take(double now_s);
  bool any() const { return any_; }                             // one came since clear()
  double age(double now_s) const { return now_s - arrived_; }  // s since the newest came
  double vx() const { return vx_; }
  double vy() const { return vy_; }
  double wz() const { return wz_; }
  void clear() { any_ = fresh_ = false; }  // starting(): what came while stopped is not a command

 private:
  double vx_ = 0, vy_ = 0, wz_ = 0, arrived_ = 0;
  bool fresh_ = false, any_ = false;
};

// odometry_t on `<controller>/<channel>` in odom_frame_id, child base_frame_id.
class OdometryOut {
 public:
  void init(ControllerContext& ctx, const std::string& channel, const std::string& odom_frame,
            const std::string& base_frame);
  // Pose from `odom` (left out with twist_only, as tricycle_controller's odom_only_twist) and the body twist.
  void publish(int64_t utime, const PlanarOdometry& odom, double vx, double vy, double wz, bool twist_only = false);

 private:
  odometry_t msg_{};
  Publisher<odometry_t> pub_;
};

// A drive: its odometry, which starts again from 0 when time goes back (a reset of the hardware) and otherwise
// carries over a restart.
class DriveController : public Controller {
 public:
  void restart(const Time& now) override {
    if (now.seconds() < last_update_) odometry_.set(0, 0, 0);
    starting(now);
  }

 protected:
  // In init(): `input` on `<name>/<channel>`, a twist that is not finite dropped, counted and logged (the first and
  // every 100th); `out` on `<name>/<channel>` in the parameters' odom_frame_id and base_frame_id.
  void take_twists(ControllerContext& ctx, TwistInput& input, const std::string& channel);
  static void publish_odometry(ControllerContext& ctx, OdometryOut& out, const std::string& channel);

  PlanarOdometry odometry_;
  double last_update_ = 0;  // s, the hardware time of the last starting() or update()
};

// `joint` claimed on `iface`, a refusal naming the parameter `key` that gave it.
JointData* claim_named(ControllerContext& ctx, const std::string& key, const std::string& joint, Interface iface);

// The parameters every drive of ros2_controllers shares: base_frame_id and odom_frame_id (read), and those for TF and
// covariances, which have no meaning here (named as not implemented when given).
std::vector<ParameterInfo> drive_frame_parameters();

// control_toolbox's RateLimiter: a command's value, its rate of change (bounds of its own while the previous value
// is positive and while it is negative) and its second derivative. A NaN maximum is no bound; a NaN minimum mirrors
// its maximum.
class RateLimiter {
 public:
  struct Bounds {
    double min_value = NAN, max_value = NAN;
    double min_rate_negative = NAN, max_rate_positive = NAN;  // units/s: the rate's range at 0 (its ends: below, above)
    double min_rate_positive = NAN;                           // the rate's least while positive (default: at 0's)
    double max_rate_negative = NAN;                           // its most while negative (default: at 0's)
    double min_second = NAN, max_second = NAN;                // units/s^2
  };
  RateLimiter() = default;
  // Throws std::invalid_argument for bounds that contradict each other (a minimum above its maximum).
  explicit RateLimiter(Bounds b);
  // v: wanted; v0, v1: the two previous outputs; dt: s. Returns the limited value.
  double limit(double v, double v0, double v1, double dt) const;

 private:
  Bounds b_;
  bool value_ = false, rate_ = false, second_ = false;
};

}  // namespace lcm_control::cm
