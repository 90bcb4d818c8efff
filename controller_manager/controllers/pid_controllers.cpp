// Controllers with their own PID (`pid: {p, i, d, i_clamp, antiwindup}`) on
// one joint (`joint`), commanded on `<name>/command` (float64_t), publishing
// `<name>/state` (controller_state_t) every 10th update:
//  effort_controllers/JointPositionController   position set point -> effort
//  effort_controllers/JointVelocityController   velocity set point -> effort
//  velocity_controllers/JointPositionController position set point -> velocity
// The position error is the plain difference, except on continuous joints
// where it is the shortest angle. Position set points are clamped to the
// URDF limits; start holds the current position (velocity: 0), PID reset.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "common/angles.hpp"
#include "controller_manager/controllers/factories.hpp"
#include "lcm_control/controller_state_t.hpp"
#include "lcm_control/float64_t.hpp"

namespace lcm_control::cm {

namespace {

class PidController : public Controller {
 public:
  PidController(Interface out, bool position_target) : out_(out), position_target_(position_target) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const std::string joint = p.string("joint");
    joint_ = ctx.claim(joint, out_);
    pid_.set_gains(p.pid("pid"));
    const PidGains& g = pid_.gains();
    if (g.i != 0 && g.i_clamp_min == 0 && g.i_clamp_max == 0)
      ctx.notes.push_back(
          fmt::format("{}/pid: i = {} but i_clamp is 0, so the integral term stays 0 (as in "
                      "control_toolbox); set i_clamp",
                      ctx.name(), g.i));
    state_.controller = ctx.name();
    state_.joint = joint;
    state_pub_ = ctx.port().publisher<controller_state_t>(ctx.channel("state"));
    const std::string name = ctx.name();
    ctx.port().subscribe<float64_t>(
        ctx.channel("command"),
        [this, name](const float64_t& m) {
          if (!std::isfinite(m.data)) {
            if (dropped_++ % 100 == 0) spdlog::warn("{}: dropped a NaN/Inf command", name);
            return;
          }
          if (running_) set_point_ = limit(m.data);
        },
        [this, name](const std::string& why) {
          if (dropped_++ % 100 == 0) spdlog::warn("{}: {}", name, why);
        });
  }

  std::vector<std::string> pid_joints() const override { return {state_.joint}; }
  Pid* pid(const std::string& joint) override { return joint == state_.joint ? &pid_ : nullptr; }

  void starting(const Time&) override {
    set_point_ = position_target_ ? limit(joint_->position) : 0.0;
    pid_.reset();
    count_ = 0;
  }

  void update(const Time& now, double period) override {
    double error, error_dot, pv, pv_dot;
    if (position_target_) {
      pv = joint_->position;
      pv_dot = joint_->velocity;
      error = joint_->continuous ? shortest_angular_distance(pv, set_point_) : set_point_ - pv;
      error_dot = -pv_dot;
    } else {
      pv = joint_->velocity;
      pv_dot = 0;
      error = set_point_ - pv;
      error_dot = 0;
    }
    double cmd;
    if (out_ == Interface::Effort && position_target_)
      cmd = pid_.compute(error, error_dot, period);  // ROS: velocity error as the D input
    else
      cmd = pid_.compute(error, period);
    if (joint_->urdf) {
      const double lim = out_ == Interface::Effort ? joint_->urdf->effort_limit : joint_->urdf->velocity_limit;
      if (lim > 0) cmd = std::clamp(cmd, -lim, lim);
    }
    joint_->command = cmd;
    if (count_++ % 10 == 0) {
      const PidGains& g = pid_.gains();
      state_.utime = now.utime;
      state_.set_point = set_point_;
      state_.process_value = pv;
      state_.process_value_dot = pv_dot;
      state_.error = error;
      state_.time_step = period;
      state_.command = cmd;
      state_.p = g.p;
      state_.i = g.i;
      state_.d = g.d;
      state_.i_clamp = g.i_clamp_max;
      state_.antiwindup = g.antiwindup;
      state_pub_.publish(state_);
    }
  }

 private:
  double limit(double target) const {
    if (!position_target_ || !joint_->urdf || !joint_->urdf->has_position_limits) return target;
    return std::clamp(target, joint_->urdf->lower, joint_->urdf->upper);
  }

  Interface out_;
  bool position_target_;
  JointData* joint_ = nullptr;
  Pid pid_;
  double set_point_ = 0;
  int64_t count_ = 0;
  controller_state_t state_;
  Publisher<controller_state_t> state_pub_;
};

}  // namespace

std::unique_ptr<Controller> make_pid_controller(const std::string& type) {
  if (type == "effort_controllers/JointVelocityController")
    return std::make_unique<PidController>(Interface::Effort, false);
  if (type == "velocity_controllers/JointPositionController")
    return std::make_unique<PidController>(Interface::Velocity, true);
  return std::make_unique<PidController>(Interface::Effort, true);
}

}  // namespace lcm_control::cm
