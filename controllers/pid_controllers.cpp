// Controllers with their own PID (`pid: {p, i, d, i_clamp, antiwindup}`) on
// one joint (`joint`), commanded on `<name>/command` (float64_t), publishing
// `<name>/state` (controller_state_t) every 10th update:
//  effort_controllers/JointPositionController   position set point -> effort
//  effort_controllers/JointVelocityController   velocity set point -> effort
//  velocity_controllers/JointPositionController position set point -> velocity
// and on several joints (`joints`, each with `<joint>/pid`), commanded on
// `<name>/command` (float64_array_t, one position per joint):
//  effort_controllers/JointGroupPositionController position set points -> efforts
// The position error is the plain difference, except on continuous joints
// where it is the shortest angle. Position set points are clamped to the
// URDF limits; start holds the current position (velocity: 0), PID reset.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "control/angles.hpp"
#include "controllers/factories.hpp"
#include "lcm_control/controller_state_t.hpp"

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
    state_pub_ = ctx.endpoints().publisher<controller_state_t>(ctx.channel("state"));
    ctx.take_commands(false, 1, [this](const double* v) {
      if (running_) set_point_ = limit(v[0]);
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
    if (out_ == Interface::Effort && position_target_) {
      cmd = pid_.compute(error, error_dot, period);  // ROS: velocity error as the D input
      joint_->damping = pid_.applied_d();
    } else {
      cmd = pid_.compute(error, period);
      if (out_ == Interface::Effort) joint_->damping = std::max(0.0, pid_.applied_p());  // error = set point - velocity
    }
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

double clamp_to_limits(const JointData& j, double target) {
  if (!j.urdf || !j.urdf->has_position_limits) return target;
  return std::clamp(target, j.urdf->lower, j.urdf->upper);
}

// effort_controllers/JointGroupPositionController: as ros_controllers, the PID gets the position error
// and differentiates it itself.
class GroupPositionPid : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    names_ = p.strings("joints");
    for (const auto& n : names_) {
      joints_.push_back(ctx.claim(n, Interface::Effort));
      const YAML::Node entry = p.node(n);
      if (!entry || !entry.IsMap() || !entry["pid"])
        throw p.error(n, "missing (required): " + n + ": {pid: {p: ..., i: ..., d: ...}} for every joint in `joints`");
      pids_.emplace_back();
      pids_.back().set_gains(Params::pid_from(entry["pid"], p.where() + "/" + n + "/pid"));
    }
    set_points_.assign(names_.size(), 0.0);
    ctx.take_commands(true, joints_.size(), [this](const double* v) {
      if (running_)
        for (size_t k = 0; k < joints_.size(); ++k) set_points_[k] = clamp_to_limits(*joints_[k], v[k]);
    });
  }

  std::vector<std::string> pid_joints() const override { return names_; }
  Pid* pid(const std::string& joint) override { return pid_of(names_, pids_, joint); }

  void starting(const Time&) override {
    for (size_t k = 0; k < joints_.size(); ++k) {
      set_points_[k] = clamp_to_limits(*joints_[k], joints_[k]->position);
      pids_[k].reset();
    }
  }

  void update(const Time&, double period) override {
    for (size_t k = 0; k < joints_.size(); ++k) {
      JointData& j = *joints_[k];
      const double error =
          j.continuous ? shortest_angular_distance(j.position, set_points_[k]) : set_points_[k] - j.position;
      double u = pids_[k].compute(error, period);
      if (j.urdf && j.urdf->effort_limit > 0) u = std::clamp(u, -j.urdf->effort_limit, j.urdf->effort_limit);
      j.command = u;
    }
  }

 private:
  std::vector<std::string> names_;
  std::vector<JointData*> joints_;
  std::vector<Pid> pids_;
  std::vector<double> set_points_;
};

}  // namespace

ControllerType pid_controller(Interface out, PidTarget target) {
  ControllerTypeInfo t;
  const bool position = target == PidTarget::Position;
  if (out == Interface::Effort)
    t.name = position ? "effort_controllers/JointPositionController" : "effort_controllers/JointVelocityController";
  else if (out == Interface::Velocity && position)
    t.name = "velocity_controllers/JointPositionController";
  else
    throw std::invalid_argument("pid_controller: no such type (a PID to a position command)");
  const char* quantity = position ? "position" : "velocity";
  t.doc = fmt::format("a PID from a {} set point to the {} command of `joint`", quantity,
                      out == Interface::Effort ? "effort" : "velocity");
  t.claims = {out, {"joint"}, "", {}};
  t.command = {"float64_t", "command", 1, quantity};
  t.parameters = {
      {"joint", "string", "", "joint", "", "the joint"},
      {"pid", "map", "", "pid", "", "{p, i, d, i_clamp, antiwindup}, p required"},
  };
  return {t, [out, position](const std::string&) { return std::make_unique<PidController>(out, position); }};
}

ControllerType group_position_pid_controller() {
  ControllerTypeInfo t;
  t.name = "effort_controllers/JointGroupPositionController";
  t.doc = "a PID per joint from position set points to efforts";
  t.claims = {Interface::Effort, {"joints"}, "", {}};
  t.command = {"float64_array_t", "command", CommandInfo::kOnePerJoint, "position"};
  t.parameters = {{"joints", "strings", "", "joints", "", "the joints, each with `<joint>: {pid: {p, i, d}}`"}};
  return {t, [](const std::string&) { return std::make_unique<GroupPositionPid>(); }};
}

}  // namespace lcm_control::cm
