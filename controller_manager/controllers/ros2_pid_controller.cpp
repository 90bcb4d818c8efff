// ROS 2's pid_controller/PidController (ros2_controllers): a PID per joint of `dof_names` from a reference to the
// `command_interface` command (position, velocity or effort), the reference and the measured state being the
// `reference_and_state_interfaces` (position or velocity; with [position, velocity] the velocity error is the PID's
// derivative input). The reference is ROS 2's ~/reference topic as numbers: `<name>/command` (float64_array_t, one
// per dof; the velocity reference is then 0). Per dof, gains.<dof>: {p, i, d, i_clamp_min/max, u_clamp_min/max,
// feedforward_gain, angle_wraparound}; as in ROS 2 a gain left out is 0 and the clamps are infinite.
// command = feedforward_gain * reference (with two interfaces: * the velocity reference) + PID(error[, error_dot]),
// clamped to u_clamp and to the URDF limit of the commanded quantity. error = reference - state, the shortest angle
// with angle_wraparound. On start, with set_current_state_as_first_setpoint (ROS 2's default) the reference is the
// state read then; without, it is NaN until a command arrives and the joint holds (position: where it is;
// velocity and effort: 0). use_external_measured_states is not implemented (the state is the joint's).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/angles.hpp"
#include "controller_manager/controllers/factories.hpp"
#include "controller_manager/controllers/ros2_gains.hpp"

namespace lcm_control::cm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


class Ros2PidController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    names_ = p.strings("dof_names");
    const std::string command = p.string("command_interface");
    const auto iface = interface_of_quantity(command);
    if (!iface)
      throw p.error("command_interface",
                    fmt::format("'{}' is not a joint command interface; use position, velocity or effort", command));
    iface_ = *iface;
    const std::vector<std::string> rs = p.strings("reference_and_state_interfaces");
    if (rs == std::vector<std::string>{"position"} || rs == std::vector<std::string>{"velocity"}) {
      state_ = rs[0] == "position" ? Interface::Position : Interface::Velocity;
    } else if (rs == std::vector<std::string>{"position", "velocity"}) {
      state_ = Interface::Position;
      with_derivative_ = true;
    } else {
      throw p.error("reference_and_state_interfaces",
                    fmt::format("[{}]: use [position], [velocity] or [position, velocity] (the second is the "
                                "derivative of the first)",
                                fmt::join(rs, ", ")));
    }
    if (p.has("reference_and_state_dof_names")) {
      const YAML::Node n = p.node("reference_and_state_dof_names");
      if (n.IsSequence() && n.size() > 0 && p.strings("reference_and_state_dof_names") != names_)
        throw p.error("reference_and_state_dof_names",
                      "other names than dof_names (a chained controller's) are not implemented; leave it out");
    }
    if (p.boolean("use_external_measured_states", false))
      throw p.error("use_external_measured_states",
                    "true is not implemented: the measured state is the joints' own; leave it out or set false");
    first_setpoint_is_state_ = p.boolean("set_current_state_as_first_setpoint", true);

    for (const auto& n : names_) joints_.push_back(ctx.claim(n, iface_));
    const size_t n = names_.size();
    pids_.resize(n);
    gains_.resize(n);
    const YAML::Node gains = p.node("gains");
    if (gains && !gains.IsMap()) throw p.error("gains", "expected a map {<dof>: {p, i, d, ...}}");
    if (gains)
      for (const auto& kv : gains) {
        const std::string dof = kv.first.as<std::string>();
        if (std::find(names_.begin(), names_.end(), dof) == names_.end())
          throw p.error("gains/" + dof, fmt::format("not one of dof_names ({})", fmt::join(names_, ", ")));
      }
    for (size_t k = 0; k < n; ++k) {
      if (gains && gains[names_[k]]) {
        gains_[k] = read_ros2_gains(gains[names_[k]], p.where() + "/gains/" + names_[k], "feedforward_gain", ctx.notes);
      } else {
        gains_[k].pid.i_clamp_max = std::numeric_limits<double>::max();
        gains_[k].pid.i_clamp_min = -std::numeric_limits<double>::max();
        ctx.notes.push_back(fmt::format("{}/gains/{}: none: every gain is 0, so the command is 0, as in ROS 2 (give "
                                        "gains: {{{}: {{p, i, d}}}})",
                                        p.where(), names_[k], names_[k]));
      }
      pids_[k].set_gains(gains_[k].pid);
    }
    reference_.assign(n, kNaN);
    reference_dot_.assign(n, kNaN);
    hold_.assign(n, 0.0);
    ctx.take_commands(true, n, [this](const double* v) {
      if (!running_) return;
      for (size_t k = 0; k < reference_.size(); ++k) {
        reference_[k] = v[k];
        reference_dot_[k] = 0.0;
      }
    });
  }

  std::vector<std::string> pid_joints() const override { return names_; }
  Pid* pid(const std::string& joint) override { return pid_of(names_, pids_, joint); }

  void starting(const Time&) override {
    for (size_t k = 0; k < joints_.size(); ++k) {
      const JointData& j = *joints_[k];
      pids_[k].reset();
      hold_[k] = iface_ == Interface::Position ? j.position : 0.0;
      if (first_setpoint_is_state_) {
        reference_[k] = state_ == Interface::Position ? j.position : j.velocity;
        reference_dot_[k] = with_derivative_ ? 0.0 : kNaN;
      } else {
        reference_[k] = reference_dot_[k] = kNaN;
      }
    }
  }

  void update(const Time&, double period) override {
    for (size_t k = 0; k < joints_.size(); ++k) {
      JointData& j = *joints_[k];
      j.damping = 0;
      const double ref = reference_[k];
      const double measured = state_ == Interface::Position ? j.position : j.velocity;
      if (!std::isfinite(ref) || !std::isfinite(measured)) {
        j.command = hold_[k];
        continue;
      }
      const Ros2Gains& g = gains_[k];
      const double error = g.wraparound ? shortest_angular_distance(measured, ref) : ref - measured;
      double u;
      if (with_derivative_) {
        const double ref_dot = reference_dot_[k];
        u = std::isfinite(ref_dot) ? ref_dot * g.feedforward : 0.0;
        if (std::isfinite(ref_dot) && std::isfinite(j.velocity)) {
          u += pids_[k].compute(error, ref_dot - j.velocity, period);
          if (iface_ == Interface::Effort && state_ == Interface::Position) j.damping = pids_[k].applied_d();
        } else {
          u += pids_[k].compute(error, period);
        }
      } else {
        u = ref * g.feedforward + pids_[k].compute(error, period);
      }
      u = std::clamp(u, g.u_min, g.u_max);
      j.command = limit(j, u);
    }
  }

 private:
  // The URDF's limit on the commanded quantity.
  double limit(const JointData& j, double u) const {
    if (!j.urdf) return u;
    switch (iface_) {
      case Interface::Position:
        return j.urdf->has_position_limits ? std::clamp(u, j.urdf->lower, j.urdf->upper) : u;
      case Interface::Velocity:
        return j.urdf->velocity_limit > 0 ? std::clamp(u, -j.urdf->velocity_limit, j.urdf->velocity_limit) : u;
      case Interface::Effort:
        return j.urdf->effort_limit > 0 ? std::clamp(u, -j.urdf->effort_limit, j.urdf->effort_limit) : u;
    }
    return u;
  }

  Interface iface_ = Interface::Effort;
  Interface state_ = Interface::Position;
  bool with_derivative_ = false;
  bool first_setpoint_is_state_ = true;
  std::vector<std::string> names_;
  std::vector<JointData*> joints_;
  std::vector<Pid> pids_;
  std::vector<Ros2Gains> gains_;
  std::vector<double> reference_, reference_dot_, hold_;
};

}  // namespace

ControllerType ros2_pid_controller() {
  ControllerTypeInfo t;
  t.name = "pid_controller/PidController";
  t.ros = RosVersion::Ros2;
  t.doc = "a PID per joint of `dof_names` from a reference (position or velocity) to the command_interface command";
  t.claims.joint_params = {"dof_names"};
  t.claims.interface_param = "command_interface";
  t.command = {"float64_array_t", "command", CommandInfo::kOnePerJoint, ""};
  t.parameters = {
      ros2_parameter("dof_names", "strings", "", "the joints, in the order of the reference's values"),
      ros2_parameter("command_interface", "string", "", "position, velocity or effort: what the PID commands"),
      ros2_parameter("reference_and_state_interfaces", "strings", "",
           "[position], [velocity] or [position, velocity] (the velocity error is the derivative input)"),
      ros2_parameter("gains", "map", "",
           "<dof>: {p, i, d, i_clamp_max/min, u_clamp_max/min, feedforward_gain, angle_wraparound}, each 0 or "
           "unclamped when left out"),
      ros2_parameter("set_current_state_as_first_setpoint", "bool", "true",
           "on start the reference is the state read then; false: none until a command comes (the joint holds)"),
      ros2_parameter("use_external_measured_states", "bool", "false", "must be false: the state is the joints' own"),
      ros2_parameter("reference_and_state_dof_names", "strings", "[]", "must be empty or dof_names (no chaining)"),
  };
  return {t, [](const std::string&) { return std::make_unique<Ros2PidController>(); }};
}

}  // namespace lcm_control::cm
