// ros2_controllers' steering_controllers_library: bicycle_steering_controller/BicycleSteeringController (one traction
// joint, one steering joint), tricycle_steering_controller/TricycleSteeringController (two traction joints, right
// then left, and one steering joint) and ackermann_steering_controller/AckermannSteeringController (two of each,
// right then left). A twist_t on `<name>/reference` (linear.x, angular.z) holds for reference_timeout s: the steering
// joints get positions and the traction joints velocities by inverse kinematics (no feedback loop); after it the
// traction joints get 0 and the steering keeps its angle. odometry_t on `<name>/odometry` every update, from the
// traction joints (their velocities, or their positions with position_feedback) and the steering angles, or from the
// reference with open_loop. Parameters as Kilted/Rolling name them (traction_joints_names, steering_joints_names,
// traction_wheel(s)_radius, traction_track_width, ...) and as Humble/Jazzy did (rear_wheels_names,
// front_wheels_names, front_steering, front_wheel_track, rear_wheels_radius, ...).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <cmath>
#include <limits>

#include "controllers/factories.hpp"
#include "controllers/mobile_base.hpp"

namespace lcm_control::cm {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

bool near_zero(double v) { return std::abs(v) < 1e-6; }

const char* type_name(SteeringKind k) {
  switch (k) {
    case SteeringKind::Bicycle: return "bicycle_steering_controller/BicycleSteeringController";
    case SteeringKind::Tricycle: return "tricycle_steering_controller/TricycleSteeringController";
    case SteeringKind::Ackermann: return "ackermann_steering_controller/AckermannSteeringController";
  }
  return "";
}

// The parameter names of one generation of ros2_controllers: Kilted's, or Humble's and Jazzy's with front_steering.
struct Keys {
  std::string traction, steering, traction_state, steering_state, radius, traction_track, steering_track;
};

Keys keys_for(SteeringKind kind, const Params& p) {
  const bool current = p.has("traction_joints_names") || p.has("steering_joints_names");
  if (current)
    return {"traction_joints_names",
            "steering_joints_names",
            "traction_joints_state_names",
            "steering_joints_state_names",
            kind == SteeringKind::Bicycle ? "traction_wheel_radius" : "traction_wheels_radius",
            "traction_track_width", "steering_track_width"};
  const bool front = p.boolean("front_steering", true);
  const std::string steer = front ? "front" : "rear", drive = front ? "rear" : "front";
  return {drive + "_wheels_names",
          steer + "_wheels_names",
          drive + "_wheels_state_names",
          steer + "_wheels_state_names",
          kind == SteeringKind::Bicycle ? drive + "_wheel_radius" : drive + "_wheels_radius",
          kind == SteeringKind::Tricycle ? "wheel_track" : drive + "_wheel_track",
          steer + "_wheel_track"};
}

class SteeringController : public DriveController {
 public:
  explicit SteeringController(SteeringKind kind) : kind_(kind) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const Keys k = keys_for(kind_, p);
    const size_t n_traction = kind_ == SteeringKind::Bicycle ? 1 : 2;
    const size_t n_steering = kind_ == SteeringKind::Ackermann ? 2 : 1;
    const char* kind = kind_ == SteeringKind::Bicycle ? "bicycle" : kind_ == SteeringKind::Tricycle ? "tricycle"
                                                                                                      : "Ackermann";
    auto names = [&](const std::string& key, size_t n, bool required) {
      if (!required && !p.has(key)) return std::vector<std::string>{};
      const YAML::Node node = p.node(key);
      if (!required && node.IsSequence() && node.size() == 0) return std::vector<std::string>{};
      std::vector<std::string> v = p.strings(key);
      if (v.size() != n)
        throw p.error(key, fmt::format("[{}]: the {} drive takes {} joint{}{}", fmt::join(v, ", "), kind, n,
                                       n == 1 ? "" : "s", n == 2 ? ", right then left" : ""));
      return v;
    };
    const std::vector<std::string> traction = names(k.traction, n_traction, true);
    const std::vector<std::string> steering = names(k.steering, n_steering, true);
    for (const auto& j : traction) traction_.push_back(claim_named(ctx, k.traction, j, Interface::Velocity));
    for (const auto& j : steering) steering_.push_back(claim_named(ctx, k.steering, j, Interface::Position));
    traction_state_ = {traction_.begin(), traction_.end()};
    steering_state_ = {steering_.begin(), steering_.end()};
    const std::vector<std::string> ts = names(k.traction_state, n_traction, false);
    for (size_t i = 0; i < ts.size(); ++i) traction_state_[i] = ctx.read(ts[i], k.traction_state);
    const std::vector<std::string> ss = names(k.steering_state, n_steering, false);
    for (size_t i = 0; i < ss.size(); ++i) steering_state_[i] = ctx.read(ss[i], k.steering_state);

    auto positive = [&](const std::string& key, const std::string& what) {
      const double v = p.number(key);
      if (!(v > 0)) throw p.error(key, fmt::format("{} m: must be > 0 ({})", v, what));
      return v;
    };
    wheelbase_ = positive("wheelbase", "the distance from the traction axle to the steering axle");
    radius_ = positive(k.radius, fmt::format("the radius of traction wheel{} '{}'", n_traction == 1 ? "" : "s",
                                             fmt::join(traction, "', '")));
    if (kind_ != SteeringKind::Bicycle)
      traction_track_ = positive(k.traction_track, fmt::format("the distance between '{}' and '{}'", traction[0],
                                                               traction[1]));
    steering_track_ = traction_track_;
    if (kind_ == SteeringKind::Ackermann && p.has(k.steering_track) && p.number(k.steering_track) > 0)
      steering_track_ = p.number(k.steering_track);
    timeout_ = p.number("reference_timeout", 1.0);
    if (!(timeout_ >= 0)) throw p.error("reference_timeout", fmt::format("{} s: must be >= 0", timeout_));
    open_loop_ = p.boolean("open_loop", false);
    position_feedback_ = p.boolean("position_feedback", false);
    reduce_until_steered_ = p.boolean("reduce_wheel_speed_until_steering_reached", false);
    const double window = p.number("velocity_rolling_window_size", 10);
    if (!(window >= 1)) throw p.error("velocity_rolling_window_size", fmt::format("{}: must be >= 1", window));
    linear_mean_ = angular_mean_ = RollingMean(size_t(window));
    take_twists(ctx, reference_, "reference");
    publish_odometry(ctx, odometry_out_, "odometry");
  }

  void starting(const Time& now) override {
    reference_.clear();
    for (JointData* j : traction_) j->command = 0;
    for (JointData* j : steering_) j->command = j->position;
    for (size_t i = 0; i < traction_state_.size(); ++i) old_position_[i] = traction_state_[i]->position;
    linear_mean_.clear();
    angular_mean_.clear();
    linear_ = angular_ = 0;
    steer_ = measured_steering();
    last_update_ = now.seconds();
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_update_ = t;
    reference_.take(t);
    double v = kNaN, w = kNaN;
    if (reference_.any() && reference_.age(t) <= timeout_) {  // timeout 0: the cycle it came in only
      v = reference_.vx();
      w = reference_.wz();
    }
    update_odometry(std::isfinite(v) ? v : 0.0, std::isfinite(w) ? w : 0.0, period);
    if (std::isfinite(v) && std::isfinite(w)) {
      write_commands(v, w);
    } else {
      for (JointData* j : traction_) j->command = 0;
    }
    odometry_out_.publish(now.utime, odometry_, linear_, 0, angular_);
  }

  void stopping(const Time&) override {
    for (JointData* j : traction_) j->command = 0;
  }

 private:
  // The steering angle of the virtual middle wheel: the one steering joint's, or Ackermann's two converted to it.
  double measured_steering() const {
    if (kind_ != SteeringKind::Ackermann) return steering_state_[0]->position;
    const double r = steering_state_[0]->position, l = steering_state_[1]->position;
    const double right = std::atan(wheelbase_ * std::tan(r) / (wheelbase_ - steering_track_ / 2 * std::tan(r)));
    const double left = std::atan(wheelbase_ * std::tan(l) / (wheelbase_ + steering_track_ / 2 * std::tan(l)));
    return (right + left) / 2;
  }

  // Traction wheel speeds in rad/s: measured, or from the position change over the period.
  double traction_speed(size_t i, double period) {
    if (!position_feedback_) return traction_state_[i]->velocity;
    const double q = traction_state_[i]->position, dq = q - old_position_[i];
    old_position_[i] = q;
    return period > 0 ? dq / period : 0.0;
  }

  // The forward speed of the base from a double traction axle turning about the steering's centre.
  double axle_speed(double right, double left, double steer) const {
    const double vr = right * radius_, vl = left * radius_;
    if (near_zero(std::tan(steer))) return (vr + vl) / 2;
    const double turning = wheelbase_ / std::tan(steer);
    return (vr * turning / (turning + traction_track_ / 2) + vl * turning / (turning - traction_track_ / 2)) / 2;
  }

  void update_odometry(double v_ref, double w_ref, double period) {
    if (open_loop_) {
      linear_ = v_ref;
      angular_ = w_ref;
      odometry_.move(v_ref * period, 0, w_ref * period);
      return;
    }
    steer_ = measured_steering();
    double v = 0;
    if (kind_ == SteeringKind::Bicycle) {
      v = traction_speed(0, period) * radius_;
    } else {
      const double right = traction_speed(0, period), left = traction_speed(1, period);
      v = axle_speed(right, left, steer_);
    }
    if (!std::isfinite(v) || !std::isfinite(steer_)) return;
    const double w = std::tan(steer_) * v / wheelbase_;
    odometry_.move(v * period, 0, w * period);
    if (period < 1e-4) return;  // too short to estimate speeds from
    linear_mean_.add(v);
    angular_mean_.add(w);
    linear_ = linear_mean_.mean();
    angular_ = angular_mean_.mean();
  }

  // ros2_controllers' SteeringKinematics::get_commands: the middle wheel's angle atan(w * wheelbase / v) (0 when
  // that is not a number), the traction speed v / radius; with two traction wheels, each for its radius about the
  // turning centre the measured steering gives; Ackermann's two steering angles for the commanded one.
  void write_commands(double v, double w) {
    double phi = std::atan(w * wheelbase_ / v);
    if (!std::isfinite(phi)) phi = 0;
    const double phi_ik = open_loop_ ? phi : steer_;
    double ws = v / radius_;
    if (!open_loop_ && reduce_until_steered_) {
      const double delta = std::abs(steer_ - phi), lowest = M_PI / 6, highest = 1.5608;
      if (delta >= lowest) ws *= std::cos(std::min(delta, highest)) / std::cos(lowest);
    }
    if (kind_ == SteeringKind::Bicycle) {
      traction_[0]->command = ws;
      steering_[0]->command = phi;
      return;
    }
    if (near_zero(phi_ik)) {
      traction_[0]->command = traction_[1]->command = ws;
    } else {
      const double turning = wheelbase_ / std::tan(phi_ik);
      traction_[0]->command = ws * (turning + traction_track_ / 2) / turning;  // right
      traction_[1]->command = ws * (turning - traction_track_ / 2) / turning;  // left
    }
    if (kind_ == SteeringKind::Tricycle) {
      steering_[0]->command = phi;
      return;
    }
    if (near_zero(phi_ik)) {
      steering_[0]->command = steering_[1]->command = phi;
      return;
    }
    const double num = 2 * wheelbase_ * std::sin(phi), den = 2 * wheelbase_ * std::cos(phi);
    steering_[0]->command = std::atan2(num, den + steering_track_ * std::sin(phi));  // right
    steering_[1]->command = std::atan2(num, den - steering_track_ * std::sin(phi));  // left
  }

  SteeringKind kind_;
  std::vector<JointData*> traction_, steering_;
  std::vector<const JointData*> traction_state_, steering_state_;
  double old_position_[2] = {0, 0};
  double wheelbase_ = 0, radius_ = 0, traction_track_ = 0, steering_track_ = 0, timeout_ = 1;
  bool open_loop_ = false, position_feedback_ = false, reduce_until_steered_ = false;
  TwistInput reference_;
  RollingMean linear_mean_, angular_mean_;
  double linear_ = 0, angular_ = 0, steer_ = 0;
  OdometryOut odometry_out_;
};

}  // namespace

ControllerType steering_controller(SteeringKind kind) {
  ControllerTypeInfo t;
  t.name = type_name(kind);
  t.ros = RosVersion::Ros2;
  const char* joints = kind == SteeringKind::Bicycle    ? "one traction and one steering joint"
                       : kind == SteeringKind::Tricycle ? "two traction joints (right, left) and one steering joint"
                                                        : "two traction and two steering joints (right, left)";
  t.doc = fmt::format("a twist_t on <name>/reference to steering positions and traction velocities ({}); "
                      "odometry_t on <name>/odometry",
                      joints);
  // The older keys name the wheels by axle: front_steering says which axle steers.
  t.claims = {Interface::Velocity, {"traction_joints_names", "rear_wheels_names", "front_wheels_names"}, "", {}};
  t.claims.also = {{Interface::Position, {"steering_joints_names", "front_wheels_names", "rear_wheels_names"}}};
  t.command = {"twist_t", "reference", 0, ""};
  t.parameters = {
      ros2_parameter("traction_joints_names", "strings", "", "the traction (drive) joints, right then left"),
      ros2_parameter("steering_joints_names", "strings", "", "the steering joints, right then left"),
      ros2_parameter("traction_joints_state_names", "strings", "[]", "joints to read the traction state from"),
      ros2_parameter("steering_joints_state_names", "strings", "[]", "joints to read the steering state from"),
      ros2_parameter("wheelbase", "number", "", "m from the traction axle to the steering axle"),
      ros2_parameter("reference_timeout", "number", "1.0",
                     "s a reference holds; then the traction stops (0: the cycle it came in only)"),
      ros2_parameter("open_loop", "bool", "false", "odometry from the reference instead of the joints"),
      ros2_parameter("position_feedback", "bool", "false", "odometry from the traction positions, not velocities"),
      ros2_parameter("reduce_wheel_speed_until_steering_reached", "bool", "false",
                     "slow the traction while the steering is far from its angle"),
      ros2_parameter("velocity_rolling_window_size", "number", "10", "samples averaged into the odometry's twist"),
      ros2_parameter("front_steering", "bool", "true",
                     "Humble/Jazzy: the front wheels steer (then rear_wheels_names drive), or the rear ones"),
      ros2_parameter("rear_wheels_names", "strings", "", "Humble/Jazzy: the rear wheel joints"),
      ros2_parameter("front_wheels_names", "strings", "", "Humble/Jazzy: the front wheel joints"),
      ros2_parameter("rear_wheels_state_names", "strings", "[]", "Humble/Jazzy: joints to read the rear state from"),
      ros2_parameter("front_wheels_state_names", "strings", "[]", "Humble/Jazzy: joints to read the front state from"),
  };
  for (ParameterInfo& f : drive_frame_parameters()) t.parameters.push_back(std::move(f));
  switch (kind) {
    case SteeringKind::Bicycle:
      t.parameters.push_back(ros2_parameter("traction_wheel_radius", "number", "", "m, the traction wheel's"));
      t.parameters.push_back(ros2_parameter("rear_wheel_radius", "number", "", "Humble/Jazzy: m"));
      t.parameters.push_back(ros2_parameter("front_wheel_radius", "number", "", "Humble/Jazzy: m"));
      break;
    case SteeringKind::Tricycle:
      t.parameters.push_back(ros2_parameter("traction_wheels_radius", "number", "", "m, the traction wheels'"));
      t.parameters.push_back(ros2_parameter("traction_track_width", "number", "", "m between the traction wheels"));
      t.parameters.push_back(ros2_parameter("wheel_track", "number", "", "Humble/Jazzy: traction_track_width"));
      t.parameters.push_back(ros2_parameter("rear_wheels_radius", "number", "", "Humble/Jazzy: m"));
      t.parameters.push_back(ros2_parameter("front_wheels_radius", "number", "", "Humble/Jazzy: m"));
      break;
    case SteeringKind::Ackermann:
      t.parameters.push_back(ros2_parameter("traction_wheels_radius", "number", "", "m, the traction wheels'"));
      t.parameters.push_back(ros2_parameter("traction_track_width", "number", "", "m between the traction wheels"));
      t.parameters.push_back(ros2_parameter("steering_track_width", "number", "",
                                            "m between the steering joints (default: traction_track_width)"));
      t.parameters.push_back(ros2_parameter("rear_wheel_track", "number", "", "Humble/Jazzy: m"));
      t.parameters.push_back(ros2_parameter("front_wheel_track", "number", "", "Humble/Jazzy: m"));
      t.parameters.push_back(ros2_parameter("rear_wheels_radius", "number", "", "Humble/Jazzy: m"));
      t.parameters.push_back(ros2_parameter("front_wheels_radius", "number", "", "Humble/Jazzy: m"));
      break;
  }
  return {t, [kind](const std::string&) { return std::make_unique<SteeringController>(kind); }};
}

}  // namespace lcm_control::cm
