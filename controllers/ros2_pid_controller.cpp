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
// Chainable (ROS 2): each dof is the reference interface "<name>/<dof>" (on the reference interface, and velocity
// with [position, velocity]); while a running controller writes them (a diff drive's wheels), the reference is
// what it wrote (its velocity part 0) and <name>/command is not read.
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "control/angles.hpp"
#include "controllers/factories.hpp"
#include "controllers/ros2_gains.hpp"

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
    // One interface, or two (ROS 2: the second is taken as the first's derivative, whatever it is: a gz demo's
    // [velocity, effort]).
    const std::vector<std::string> rs = p.strings("reference_and_state_interfaces");
    std::vector<Interface> read;
    for (const std::string& r : rs)
      if (const auto i = interface_of_quantity(r)) read.push_back(*i);
    if (rs.empty() || rs.size() > 2 || read.size() != rs.size() || (read.size() == 2 && read[0] == read[1]))
      throw p.error("reference_and_state_interfaces",
                    fmt::format("[{}]: give one or two different ones of position, velocity and effort (the second is "
                                "the derivative of the first: [position, velocity])",
                                fmt::join(rs, ", ")));
    state_ = read[0];
    with_derivative_ = read.size() == 2;
    if (with_derivative_) derivative_ = read[1];
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
    // Chainable: "<name>/<dof>" is a reference interface a preceding controller may write (a diff drive's wheel
    // velocity), showing the dof's state; while one does, the references come from there, not <name>/command.
    std::vector<Interface> exported{state_};
    if (with_derivative_) exported.push_back(derivative_);
    for (size_t k = 0; k < n; ++k) refs_.push_back(ctx.export_reference(names_[k], exported, joints_[k]));
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
      if (!running_ || chained_mode()) return;  // chained: the preceding controller's references count
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
        reference_[k] = value_of(j, state_);
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
      if (chained_mode()) {  // the reference a preceding controller wrote in this cycle (a velocity reference: 0)
        reference_[k] = refs_[k]->command;
        reference_dot_[k] = with_derivative_ ? 0.0 : kNaN;
      }
      const double ref = reference_[k];
      const double measured = value_of(j, state_);
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
        const double measured_dot = value_of(j, derivative_);
        if (std::isfinite(ref_dot) && std::isfinite(measured_dot)) {
          u += pids_[k].compute(error, ref_dot - measured_dot, period);
          if (iface_ == Interface::Effort && state_ == Interface::Position && derivative_ == Interface::Velocity)
            j.damping = pids_[k].applied_d();
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
  static double value_of(const JointData& j, Interface i) {
    return i == Interface::Position ? j.position : i == Interface::Velocity ? j.velocity : j.effort;
  }

  Interface state_ = Interface::Position, derivative_ = Interface::Velocity;
  bool with_derivative_ = false;
  bool first_setpoint_is_state_ = true;
  std::vector<std::string> names_;
  std::vector<JointData*> joints_;
  std::vector<JointData*> refs_;  // the reference interfaces it exports, one per dof
  std::vector<Pid> pids_;
  std::vector<Ros2Gains> gains_;
  std::vector<double> reference_, reference_dot_, hold_;
};

}  // namespace

ControllerType ros2_pid_controller() {
  ControllerTypeInfo t;
  t.name = "pid_controller/PidController";
  t.ros = RosVersion::Ros2;
  t.chainable = true;
  t.references = "<name>/<dof> for each of dof_names, on its reference_and_state_interfaces";
  t.doc = "a PID per joint of `dof_names` from a reference (position or velocity) to the command_interface command; "
          "chainable: <name>/<dof> are reference interfaces another controller may write";
  t.claims.joint_params = {"dof_names"};
  t.claims.interface_param = "command_interface";
  t.command = {"float64_array_t", "command", CommandInfo::kOnePerJoint, ""};
  t.parameters = {
      ros2_parameter("dof_names", "strings", "", "the joints, in the order of the reference's values"),
      ros2_parameter("command_interface", "string", "", "position, velocity or effort: what the PID commands"),
      ros2_parameter("reference_and_state_interfaces", "strings", "",
           "one or two of position, velocity, effort (the second's error is the derivative input: [position, "
           "velocity])"),
      ros2_parameter("gains", "map", "",
           "<dof>: {p, i, d, i_clamp_max/min, u_clamp_max/min, feedforward_gain, angle_wraparound}, each 0 or "
           "unclamped when left out"),
      ros2_parameter("set_current_state_as_first_setpoint", "bool", "true",
           "on start the reference is the state read then; false: none until a command comes (the joint holds)"),
      ros2_parameter("use_external_measured_states", "bool", "false", "must be false: the state is the joints' own"),
      ros2_parameter("reference_and_state_dof_names", "strings", "[]", "must be empty or dof_names"),
  };
  return {t, [](const std::string&) { return std::make_unique<Ros2PidController>(); }};
}

}  // namespace lcm_control::cm
