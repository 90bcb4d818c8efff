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

namespace lcm_control::cm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The keys of ROS 2's gains.<dof>.
const char* const kGainKeys[] = {"p", "i", "d", "i_clamp_max", "i_clamp_min", "u_clamp_max", "u_clamp_min",
                                 "feedforward_gain", "angle_wraparound", "antiwindup", "antiwindup_strategy",
                                 "tracking_time_constant", "error_deadband", "save_i_term",
                                 "activate_state_publisher"};

struct DofGains {
  PidGains pid;
  double feedforward = 0, u_min = -kInf, u_max = kInf;
  bool wraparound = false;
};

// gains.<dof> as ROS 2 reads it: p, i, d default 0, the integral unclamped unless i_clamp_* say otherwise.
DofGains ros2_pid_gains(const YAML::Node& node, const std::string& where, std::vector<std::string>& notes) {
  if (!node.IsMap())
    throw ControllerError(where + ": expected a map {p, i, d, i_clamp_max, i_clamp_min, u_clamp_max, u_clamp_min, "
                                  "feedforward_gain, angle_wraparound}");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (std::find_if(std::begin(kGainKeys), std::end(kGainKeys), [&](const char* k) { return key == k; }) ==
        std::end(kGainKeys))
      throw ControllerError(fmt::format("{}/{}: unknown key; valid keys are {}", where, key, fmt::join(kGainKeys, ", ")));
  }
  DofGains out;
  YAML::Node g = YAML::Clone(node);
  auto take = [&](const char* key, double& value) {
    if (!g[key]) return;
    try {
      value = g[key].as<double>();
    } catch (const YAML::Exception&) {
      throw ControllerError(fmt::format("{}/{}: '{}' is not a number", where, key, g[key].Scalar()));
    }
    if (std::isnan(value)) throw ControllerError(fmt::format("{}/{}: is not a number", where, key));
    g.remove(key);
  };
  take("feedforward_gain", out.feedforward);
  take("u_clamp_min", out.u_min);
  take("u_clamp_max", out.u_max);
  if (out.u_min > out.u_max)
    throw ControllerError(fmt::format("{}: u_clamp_min {} is above u_clamp_max {}", where, out.u_min, out.u_max));
  if (g["angle_wraparound"]) {
    try {
      out.wraparound = g["angle_wraparound"].as<bool>();
    } catch (const YAML::Exception&) {
      throw ControllerError(
          fmt::format("{}/angle_wraparound: '{}' is not true or false", where, g["angle_wraparound"].Scalar()));
    }
    g.remove("angle_wraparound");
  }
  if (g["antiwindup_strategy"] && g["antiwindup_strategy"].IsScalar() && g["antiwindup_strategy"].Scalar() != "none")
    notes.push_back(fmt::format("{}/antiwindup_strategy: '{}' is not implemented; the integral term is clamped to "
                                "i_clamp_min/max",
                                where, g["antiwindup_strategy"].Scalar()));
  for (const char* ignored : {"antiwindup_strategy", "tracking_time_constant", "error_deadband", "save_i_term",
                              "activate_state_publisher"})
    g.remove(ignored);
  // ROS 2's i_clamp defaults are infinite; here a clamp of 0 would zero the I term, so "none" is the largest number.
  constexpr double kBig = std::numeric_limits<double>::max();
  auto clamp_or_big = [&](const char* key, double big) {
    if (!g[key]) return;
    try {
      if (std::isinf(g[key].as<double>())) g[key] = big;
    } catch (const YAML::Exception&) {
    }  // pid_from names it
  };
  clamp_or_big("i_clamp_max", kBig);
  clamp_or_big("i_clamp_min", -kBig);
  const bool has_max = static_cast<bool>(g["i_clamp_max"]), has_min = static_cast<bool>(g["i_clamp_min"]);
  if (!g["p"]) g["p"] = 0.0;
  out.pid = Params::pid_from(g, where);
  if (!has_max) out.pid.i_clamp_max = kBig;
  if (!has_min) out.pid.i_clamp_min = -kBig;
  return out;
}

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
        gains_[k] = ros2_pid_gains(gains[names_[k]], p.where() + "/gains/" + names_[k], ctx.notes);
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
  Pid* pid(const std::string& joint) override {
    for (size_t k = 0; k < names_.size(); ++k)
      if (names_[k] == joint) return &pids_[k];
    return nullptr;
  }

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
      const double ref = reference_[k];
      const double measured = state_ == Interface::Position ? j.position : j.velocity;
      if (!std::isfinite(ref) || !std::isfinite(measured)) {
        j.command = hold_[k];
        continue;
      }
      const DofGains& g = gains_[k];
      const double error = g.wraparound ? shortest_angular_distance(measured, ref) : ref - measured;
      double u;
      if (with_derivative_) {
        const double ref_dot = reference_dot_[k];
        u = std::isfinite(ref_dot) ? ref_dot * g.feedforward : 0.0;
        if (std::isfinite(ref_dot) && std::isfinite(j.velocity))
          u += pids_[k].compute(error, ref_dot - j.velocity, period);
        else
          u += pids_[k].compute(error, period);
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
  std::vector<DofGains> gains_;
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
  auto ros2 = [](const char* name, const char* type, const char* fallback, const char* doc) {
    return ParameterInfo{name, type, fallback, "", name, doc, true};
  };
  t.parameters = {
      ros2("dof_names", "strings", "", "the joints, in the order of the reference's values"),
      ros2("command_interface", "string", "", "position, velocity or effort: what the PID commands"),
      ros2("reference_and_state_interfaces", "strings", "",
           "[position], [velocity] or [position, velocity] (the velocity error is the derivative input)"),
      ros2("gains", "map", "",
           "<dof>: {p, i, d, i_clamp_max/min, u_clamp_max/min, feedforward_gain, angle_wraparound}, each 0 or "
           "unclamped when left out"),
      ros2("set_current_state_as_first_setpoint", "bool", "true",
           "on start the reference is the state read then; false: none until a command comes (the joint holds)"),
      ros2("use_external_measured_states", "bool", "false", "must be false: the state is the joints' own"),
      ros2("reference_and_state_dof_names", "strings", "[]", "must be empty or dof_names (no chaining)"),
  };
  return {t, [](const std::string&) { return std::make_unique<Ros2PidController>(); }};
}

}  // namespace lcm_control::cm
