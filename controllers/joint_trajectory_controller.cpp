// {position,velocity,effort}_controllers/JointTrajectoryController with
// ros_controllers' parameters: `joints`, `gains/<joint>` (velocity and effort:
// PID on the position error with the velocity error as the D input),
// `velocity_ff/<joint>` (velocity and effort: times the desired velocity, added),
// `constraints: {goal_time, stopped_velocity_tolerance, <joint>: {trajectory,
// goal}}` (0 = not checked), `state_publish_rate` (`<name>/state`,
// joint_trajectory_controller_state_t; 0: never), `action_monitor_rate`,
// `stop_trajectory_duration` (the ramp to rest on start, on a path tolerance
// violation and on an empty trajectory), `allow_partial_joints_goal` (joints a
// goal leaves out hold their desired position).
// Goals arrive on `<name>/command` (joint_trajectory_t, times relative to the
// cycle that receives them; a new goal preempts the running one; one without
// points stops). Feedback on `<name>/feedback`, one result per goal on
// `<name>/result` (trajectory_status_t), naming the joint and the error when
// a tolerance is violated.
// joint_trajectory_controller/JointTrajectoryController (ROS 2) is the same
// controller with ROS 2's parameters: `command_interfaces` chooses the
// interface ([position], [position, velocity(, acceleration)] and
// [position, effort] command positions: the hardware takes one command per
// joint; [velocity], [effort] use `gains` (default 0, as ROS 2, with
// ff_velocity_scale), or with open_loop_control and [velocity] the desired
// velocity as it is), `state_interfaces` are checked, `interpolation_method:
// none` steps from waypoint to waypoint, and `cmd_timeout` (> goal_time) holds
// the measured position that long after a trajectory's end.
#include <endian.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <optional>

#include "control/angles.hpp"
#include "controllers/factories.hpp"
#include "controllers/ros2_gains.hpp"
#include "controllers/trajectory.hpp"
#include "lcm_control/joint_trajectory_controller_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "rt/log.hpp"

namespace lcm_control::cm {

namespace {

double non_negative(const YAML::Node& x, const std::string& where) {
  try {
    const double v = x.as<double>();
    if (!std::isfinite(v) || v < 0) throw YAML::Exception(YAML::Mark::null_mark(), "");
    return v;
  } catch (const YAML::Exception&) {
    throw ControllerError(fmt::format("{}: expected a number >= 0", where));
  }
}

// ROS 2's `command_interfaces` as the one interface the hardware takes.
Interface ros2_command_interface(Params& p, std::vector<std::string>& notes) {
  const std::vector<std::string> c = p.strings("command_interfaces");
  auto is = [&c](std::initializer_list<const char*> set) {
    if (c.size() != set.size()) return false;
    for (const char* x : set)
      if (std::find(c.begin(), c.end(), x) == c.end()) return false;
    return true;
  };
  if (is({"position"})) return Interface::Position;
  if (is({"velocity"})) return Interface::Velocity;
  if (is({"effort"})) return Interface::Effort;
  if (is({"position", "velocity"}) || is({"position", "velocity", "acceleration"}) || is({"position", "effort"})) {
    notes.push_back(fmt::format("{}/command_interfaces: [{}]: the joints are commanded in position (the hardware "
                                "takes one command per joint; the others are not sent)",
                                p.where(), fmt::join(c, ", ")));
    return Interface::Position;
  }
  throw p.error("command_interfaces", fmt::format("[{}] is not a combination ROS 2 allows; use [position], [velocity], "
                                                  "[effort], [position, velocity], [position, velocity, acceleration] "
                                                  "or [position, effort]",
                                                  fmt::join(c, ", ")));
}

// What a goal is checked and planned against off the loop: fixed when the controller is made.
struct Limit {
  bool has = false;
  double lower = 0, upper = 0;
};
struct GoalRules {
  std::vector<std::string> joints;
  std::vector<char> continuous;
  std::vector<Limit> limits;
  bool allow_partial = false, interpolate = true;
};
struct GoalIds {
  int64_t utime = 0, goal_id = 0;
};
// A goal as prepared off the loop: refused (error), an empty trajectory (stop), or planned.
struct PreparedGoal {
  GoalIds ids;
  std::string error;
  bool empty = false;
  std::vector<int> index;        // controller joint -> goal column (-1: left out)
  std::vector<double> first;     // each joint's first position
  std::vector<char> continuous;
  Trajectory::Plan plan;
  int beyond = 0;                // positions beyond a joint limit; the first is named in limit_note
  std::string limit_note;
  double duration = 0;
};

class JointTrajectoryController : public Controller {
 public:
  // No `iface`: ROS 2's controller, whose command_interfaces choose it.
  explicit JointTrajectoryController(std::optional<Interface> iface)
      : iface_(iface.value_or(Interface::Position)), ros2_(!iface) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    name_ = ctx.name();
    names_ = p.strings("joints");
    if (ros2_) read_ros2_interfaces(p, ctx.notes);
    // ROS 2's command_joints (chaining): what it commands, one per joint, e.g. the reference interfaces of a PID
    // ("<pid>/<joint>"); the state stays that of `joints`.
    const std::vector<std::string> commanded = ros2_ && p.has("command_joints") ? p.strings("command_joints")
                                                                               : std::vector<std::string>{};
    if (!commanded.empty() && commanded.size() != names_.size())
      throw p.error("command_joints", fmt::format("{} name(s) for {} joint(s): give one per joint of `joints`, in "
                                                  "its order",
                                                  commanded.size(), names_.size()));
    for (size_t k = 0; k < names_.size(); ++k) {
      joints_.push_back(ctx.claim(commanded.empty() ? names_[k] : commanded[k], iface_));
      states_.push_back(commanded.empty() ? joints_.back() : ctx.read(names_[k], "joints"));
    }
    const size_t n = names_.size();
    read_constraints(p);
    u_min_.assign(n, -std::numeric_limits<double>::infinity());
    u_max_.assign(n, std::numeric_limits<double>::infinity());
    if (ros2_ && iface_ != Interface::Position) {
      pids_.resize(n);
      velocity_ff_.assign(n, 0.0);
      const YAML::Node gains = p.node("gains");
      if (gains && !gains.IsMap()) throw p.error("gains", "expected a map {<joint>: {p, i, d, ff_velocity_scale}}");
      if (!open_loop_ && (!gains || gains.size() == 0))
        ctx.notes.push_back(fmt::format("{}: no gains: every gain is 0, so the {} command is 0, as in ROS 2 (give "
                                        "gains: {{<joint>: {{p, i, d, ff_velocity_scale}}}})",
                                        p.where(), quantity_of(iface_)));
      for (size_t k = 0; k < n && gains; ++k)
        if (gains[names_[k]]) {
          const Ros2Gains g =
              read_ros2_gains(gains[names_[k]], p.where() + "/gains/" + names_[k], "ff_velocity_scale", ctx.notes);
          pids_[k].set_gains(g.pid);
          velocity_ff_[k] = g.feedforward;
          u_min_[k] = g.u_min;
          u_max_[k] = g.u_max;
        }
    } else if (iface_ != Interface::Position) {
      const YAML::Node gains = p.node("gains");
      if (!gains || !gains.IsMap())
        throw p.error("gains", fmt::format("missing (required for {}): gains: {{<joint>: {{p, i, d}}}} per joint",
                                           to_string(iface_)));
      pids_.resize(n);
      for (size_t k = 0; k < n; ++k) {
        const std::string where = p.where() + "/gains/" + names_[k];
        if (!gains[names_[k]]) throw ControllerError(where + ": missing (required): {p, i, d, i_clamp}");
        pids_[k].set_gains(Params::pid_from(gains[names_[k]], where));
      }
      velocity_ff_.assign(n, 0.0);
      if (const YAML::Node ff = p.node("velocity_ff")) {
        if (!ff.IsMap()) throw p.error("velocity_ff", "expected a map {<joint>: factor}");
        for (const auto& kv : ff) {
          const std::string joint = kv.first.as<std::string>();
          const auto it = std::find(names_.begin(), names_.end(), joint);
          if (it == names_.end())
            throw p.error("velocity_ff/" + joint, fmt::format("not one of this controller's joints ({})",
                                                              fmt::join(names_, ", ")));
          velocity_ff_[it - names_.begin()] = non_negative(kv.second, p.where() + "/velocity_ff/" + joint);
        }
      }
    } else if (p.has("gains") || p.has("velocity_ff")) {
      ctx.notes.push_back(fmt::format("{}: gains{} are not used with the position interface", name_,
                                      ros2_ ? "" : " and velocity_ff"));
      p.node("gains");
      p.node("velocity_ff");
    }
    monitor_rate_ = p.number("action_monitor_rate", 20.0);
    if (monitor_rate_ <= 0) throw p.error("action_monitor_rate", "must be > 0");
    state_rate_ = p.number("state_publish_rate", 50.0);
    if (state_rate_ < 0) throw p.error("state_publish_rate", "must be >= 0 (0: never)");
    stop_duration_ = p.number("stop_trajectory_duration", 0.0);
    if (stop_duration_ < 0) throw p.error("stop_trajectory_duration", "must be >= 0 seconds");
    allow_partial_ = p.boolean("allow_partial_joints_goal", false);
    if (ros2_) read_ros2_options(p, ctx.notes);

    desired_.resize(n);
    rest_from_.resize(n);
    hold_pos_.assign(n, 0.0);
    max_path_err_.assign(n, 0.0);
    hold_ = Trajectory::hold(0, hold_pos_);
    current_ = &hold_;
    status_.num_joints = static_cast<int32_t>(n);
    status_.joint_names = names_;
    status_.desired.assign(n, 0.0);
    status_.actual.assign(n, 0.0);
    status_.error.assign(n, 0.0);
    status_.message.reserve(1024);
    state_.num_joints = static_cast<int32_t>(n);
    state_.joint_names = names_;
    for (auto* v : {&state_.desired_position, &state_.desired_velocity, &state_.desired_acceleration,
                    &state_.actual_position, &state_.actual_velocity, &state_.error_position, &state_.error_velocity})
      v->assign(n, 0.0);
    feedback_pub_ = ctx.endpoints().publisher<trajectory_status_t>(ctx.channel("feedback"));
    result_pub_ = ctx.endpoints().publisher<trajectory_status_t>(ctx.channel("result"));
    state_pub_ = ctx.endpoints().publisher<joint_trajectory_controller_state_t>(ctx.channel("state"));
    // A goal is decoded, checked and planned off the loop (Endpoints::subscribe_off_loop), from what never changes
    // once the controller is made (the rules); the loop takes it whole between cycles.
    auto rules = std::make_shared<GoalRules>();
    rules->joints = names_;
    for (const JointData* j : states_) {
      rules->continuous.push_back(j->continuous);
      rules->limits.push_back(j->urdf && j->urdf->has_position_limits ? Limit{true, j->urdf->lower, j->urdf->upper}
                                                                      : Limit{});
    }
    rules->allow_partial = allow_partial_;
    rules->interpolate = interpolate_;
    endpoints_ = &ctx.endpoints();
    ctx.endpoints().subscribe_off_loop<joint_trajectory_t>(
        ctx.channel("command"),
        [this, rules](const joint_trajectory_t& g) -> Intake::Result {
          auto goal = std::make_shared<PreparedGoal>(prepare_goal(*rules, g));
          return [this, goal] { take_goal(*goal); };
        },
        [this](const std::string& why) {
          ++dropped_;
          bad_log_.warn(fmt::format("{}: {}", name_, why));
        });
    // A goal too large to take, or lost on the way: its sender hears of it on the result channel, under the goal id
    // its first bytes carry (a joint_trajectory_t starts with its fingerprint, utime and goal_id).
    ctx.endpoints().on_lost(ctx.channel("command"), [this](const LcmSocket::Lost& lost) {
      int64_t hash = 0;
      if (lost.head_size >= 24) std::memcpy(&hash, lost.head, 8);
      if (int64_t(be64toh(uint64_t(hash))) != joint_trajectory_t::getHash()) return;  // not a goal: no id to answer
      joint_trajectory_t g;
      std::memcpy(&g.utime, lost.head + 8, 8);
      std::memcpy(&g.goal_id, lost.head + 16, 8);
      g.utime = int64_t(be64toh(uint64_t(g.utime)));
      g.goal_id = int64_t(be64toh(uint64_t(g.goal_id)));
      answer(GoalIds{g.utime, g.goal_id}, trajectory_status_t::REJECTED,
             fmt::format("{}: goal {} rejected: {}", name_, g.goal_id, describe(lost)));
    });
  }

  std::vector<std::string> pid_joints() const override {
    return iface_ != Interface::Position ? names_ : std::vector<std::string>{};
  }
  Pid* pid(const std::string& joint) override { return pid_of(names_, pids_, joint); }

  void restart(const Time& now) override {
    if (goal_active_)
      finish(now, trajectory_status_t::PREEMPTED,
             "controller restarted from the current state (hardware restarted, resumed or jumped in time)");
    starting(now);
  }

  void starting(const Time& now) override {
    if (goal_active_) finish(now, trajectory_status_t::PREEMPTED, "controller restarted");
    for (size_t k = 0; k < joints_.size(); ++k) rest_from_[k] = {states_[k]->position, states_[k]->velocity, 0.0};
    hold_.set_stop(now.seconds(), stop_duration_, rest_from_.data());
    current_ = &hold_;
    for (auto& pid : pids_) pid.reset();
    last_t_ = now.seconds();
    last_state_ = -1e9;
  }

  void stopping(const Time& now) override {
    if (goal_active_) finish(now, trajectory_status_t::PREEMPTED, "controller stopped");
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_t_ = t;
    size_t worst = 0;
    double worst_excess = 0;
    for (size_t k = 0; k < joints_.size(); ++k) {
      JointData& j = *joints_[k];
      const JointData& s = *states_[k];
      current_->sample(t, k, desired_[k]);
      const double e =
          s.continuous ? shortest_angular_distance(s.position, desired_[k].pos) : desired_[k].pos - s.position;
      const double e_dot = desired_[k].vel - s.velocity;
      status_.desired[k] = desired_[k].pos;
      status_.actual[k] = s.position;
      status_.error[k] = e;
      state_.error_velocity[k] = e_dot;
      if (iface_ == Interface::Position) {
        j.command = desired_[k].pos;
      } else if (open_loop_) {
        j.command = desired_[k].vel;
      } else {
        double u = std::clamp(velocity_ff_[k] * desired_[k].vel + pids_[k].compute(e, e_dot, period), u_min_[k],
                              u_max_[k]);
        const double limit = !s.urdf                          ? 0
                             : iface_ == Interface::Effort   ? s.urdf->effort_limit
                                                             : s.urdf->velocity_limit;
        if (limit > 0) u = std::clamp(u, -limit, limit);
        j.command = u;
        if (iface_ == Interface::Effort) j.damping = pids_[k].applied_d();
      }
      if (goal_active_ && std::abs(e) > max_path_err_[k]) max_path_err_[k] = std::abs(e);
      if (goal_active_ && t < current_->end_time() && path_tol_[k] > 0 && std::abs(e) - path_tol_[k] > worst_excess) {
        worst_excess = std::abs(e) - path_tol_[k];
        worst = k;
      }
    }
    publish_state(now);
    if (cmd_timeout_ > 0 && current_ == &active_ && t > current_->end_time() + cmd_timeout_) {
      if (goal_active_) finish(now, trajectory_status_t::ABORTED, "command timeout: cmd_timeout passed after the end");
      for (size_t k = 0; k < joints_.size(); ++k) hold_pos_[k] = states_[k]->position;
      hold_.set_hold(t, hold_pos_.data());
      current_ = &hold_;
      return;
    }
    if (!goal_active_) return;
    if (worst_excess > 0) {
      std::snprintf(text_, sizeof text_,
                    "path tolerance violated on joint '%s': error %.6f exceeds %.6f at %.3f s of %.3f s",
                    names_[worst].c_str(), status_.error[worst], path_tol_[worst], t - current_->start_time(),
                    current_->end_time() - current_->start_time());
      finish(now, trajectory_status_t::PATH_TOLERANCE_VIOLATED, text_);
      for (size_t k = 0; k < joints_.size(); ++k) rest_from_[k] = {states_[k]->position, states_[k]->velocity, 0.0};
      hold_.set_stop(t, stop_duration_, rest_from_.data());
      current_ = &hold_;
      return;
    }
    if (t >= current_->end_time()) check_goal(now);
    if (goal_active_ && t - last_feedback_ >= 1.0 / monitor_rate_) {
      last_feedback_ = t;
      status_.utime = now.utime;
      status_.goal_id = goal_id_;
      status_.status = trajectory_status_t::ACTIVE;
      status_.message.clear();
      feedback_pub_.publish(status_);
    }
  }

 private:
  void read_ros2_interfaces(Params& p, std::vector<std::string>& notes) {
    iface_ = ros2_command_interface(p, notes);
    if (p.has("state_interfaces")) {
      const std::vector<std::string> s = p.strings("state_interfaces");
      const std::vector<std::string> order = {"position", "velocity", "acceleration"};
      bool ok = s.size() <= order.size();
      for (size_t k = 0; ok && k < s.size(); ++k) ok = s[k] == order[k];
      if (!ok)
        throw p.error("state_interfaces", fmt::format("[{}]: use [position], [position, velocity] or [position, "
                                                      "velocity, acceleration]",
                                                      fmt::join(s, ", ")));
    }
    open_loop_ = p.boolean("open_loop_control", false) && iface_ == Interface::Velocity;
  }

  void read_ros2_options(Params& p, std::vector<std::string>& notes) {
    const std::string method = p.has("interpolation_method") ? p.string("interpolation_method") : "splines";
    if (method != "splines" && method != "none")
      throw p.error("interpolation_method", fmt::format("'{}': use splines or none", method));
    interpolate_ = method == "splines";
    cmd_timeout_ = p.number("cmd_timeout", 0.0);
    if (cmd_timeout_ > 0 && cmd_timeout_ <= goal_time_) {
      notes.push_back(fmt::format("{}/cmd_timeout: {:g} s is not more than constraints/goal_time {:g} s, so it is off "
                                  "(as in ROS 2)",
                                  p.where(), cmd_timeout_, goal_time_));
      cmd_timeout_ = 0;
    }
  }

  void read_constraints(Params& p) {
    const size_t n = names_.size();
    path_tol_.assign(n, 0.0);
    goal_tol_.assign(n, 0.0);
    const YAML::Node c = p.node("constraints");
    if (!c) return;
    if (!c.IsMap()) throw p.error("constraints", "expected a map");
    const std::string where = p.where() + "/constraints";
    for (const auto& kv : c) {
      const std::string key = kv.first.as<std::string>();
      if (key == "goal_time") {
        goal_time_ = non_negative(kv.second, where + "/" + key);
      } else if (key == "stopped_velocity_tolerance") {
        stopped_vel_tol_ = non_negative(kv.second, where + "/" + key);
      } else {
        const auto it = std::find(names_.begin(), names_.end(), key);
        if (it == names_.end())
          throw ControllerError(fmt::format("{}/{}: not one of this controller's joints ({}) nor goal_time / "
                                            "stopped_velocity_tolerance",
                                            where, key, fmt::join(names_, ", ")));
        if (!kv.second.IsMap()) throw ControllerError(fmt::format("{}/{}: expected {{trajectory, goal}}", where, key));
        const size_t k = it - names_.begin();
        for (const auto& t : kv.second) {
          const std::string tk = t.first.as<std::string>();
          if (tk == "trajectory")
            path_tol_[k] = non_negative(t.second, where + "/" + key + "/trajectory");
          else if (tk == "goal")
            goal_tol_[k] = non_negative(t.second, where + "/" + key + "/goal");
          else
            throw ControllerError(fmt::format("{}/{}/{}: unknown key; use trajectory and goal", where, key, tk));
        }
      }
    }
  }

  void publish_state(const Time& now) {
    const double t = now.seconds();
    if (state_rate_ <= 0 || t - last_state_ < 1.0 / state_rate_ - 1e-9) return;
    last_state_ = t;
    state_.utime = now.utime;
    for (size_t k = 0; k < joints_.size(); ++k) {
      state_.desired_position[k] = desired_[k].pos;
      state_.desired_velocity[k] = desired_[k].vel;
      state_.desired_acceleration[k] = desired_[k].acc;
      state_.actual_position[k] = states_[k]->position;
      state_.actual_velocity[k] = states_[k]->velocity;
      state_.error_position[k] = status_.error[k];
    }
    state_pub_.publish(state_);
  }

  void check_goal(const Time& now) {
    const double t = now.seconds();
    bool within = true;
    size_t bad = 0;
    for (size_t k = 0; k < joints_.size() && within; ++k) {
      const bool pos_ok = goal_tol_[k] <= 0 || std::abs(status_.error[k]) <= goal_tol_[k];
      const bool vel_ok = stopped_vel_tol_ <= 0 || std::abs(states_[k]->velocity) <= stopped_vel_tol_;
      if (!pos_ok || !vel_ok) within = false, bad = k;
    }
    if (within) {
      size_t wf = 0, wp = 0;
      for (size_t k = 0; k < joints_.size(); ++k) {
        if (std::abs(status_.error[k]) > std::abs(status_.error[wf])) wf = k;
        if (max_path_err_[k] > max_path_err_[wp]) wp = k;
      }
      std::snprintf(text_, sizeof text_,
                    "goal %lld reached: largest final error %.6f (joint '%s'), largest path error %.6f (joint '%s')",
                    static_cast<long long>(goal_id_), std::abs(status_.error[wf]), names_[wf].c_str(),
                    max_path_err_[wp], names_[wp].c_str());
      finish(now, trajectory_status_t::SUCCEEDED, text_);
    } else if (!(ros2_ && goal_time_ == 0) && t > current_->end_time() + goal_time_) {  // ROS 2: 0 waits
      std::snprintf(text_, sizeof text_,
                    "goal tolerance violated on joint '%s': error %.6f (tolerance %.6f), velocity %.6f (stopped "
                    "tolerance %.6f), %.3f s after the trajectory end (goal_time %.3f)",
                    names_[bad].c_str(), status_.error[bad], goal_tol_[bad], states_[bad]->velocity, stopped_vel_tol_,
                    t - current_->end_time(), goal_time_);
      finish(now, trajectory_status_t::GOAL_TOLERANCE_VIOLATED, text_);
    }
  }

  void finish(const Time& now, int8_t status, const char* message) {
    status_.utime = now.utime;
    status_.goal_id = goal_id_;
    status_.status = status;
    status_.message.assign(message);
    status_.message.append(limit_note_);
    result_pub_.publish(status_);
    goal_active_ = false;
  }

  void answer(const GoalIds& g, int8_t status, const std::string& message) {
    trajectory_status_t r;
    r.utime = g.utime;
    r.goal_id = g.goal_id;
    r.status = status;
    r.message = message;
    r.num_joints = 0;
    result_pub_.publish(r);
  }

  void reject(const GoalIds& g, const std::string& why) {
    const std::string message = fmt::format("{}: goal {} rejected: {}", name_, g.goal_id, why);
    answer(g, trajectory_status_t::REJECTED, message);
    goal_log_.warn(message);
  }

  // An empty trajectory: stop where the trajectory is now, ramping down over stop_trajectory_duration.
  void stop(const GoalIds& g) {
    if (goal_active_) {
      std::snprintf(text_, sizeof text_, "stopped by an empty trajectory (goal %lld)", static_cast<long long>(g.goal_id));
      finish(Time{static_cast<int64_t>(last_t_ * 1e6)}, trajectory_status_t::PREEMPTED, text_);
    }
    for (size_t k = 0; k < names_.size(); ++k) current_->sample(last_t_, k, rest_from_[k]);
    hold_.set_stop(last_t_, stop_duration_, rest_from_.data());
    current_ = &hold_;
    answer(g, trajectory_status_t::SUCCEEDED,
           fmt::format("{}: goal {}: empty trajectory, stopping (over {:g} s)", name_, g.goal_id, stop_duration_));
    goal_log_.info(fmt::format("{}: goal {}: empty trajectory, stopping", name_, g.goal_id));
  }

  // Off the loop (the intake's thread): the goal checked and planned from the rules alone. What needs the
  // controller's state (running, where the trajectory is now) is left to take_goal().
  static PreparedGoal prepare_goal(const GoalRules& r, const joint_trajectory_t& g) {
    PreparedGoal out;
    out.ids = {g.utime, g.goal_id};
    auto refuse = [&out](std::string why) {
      out.error = std::move(why);
      return std::move(out);
    };
    const size_t n = r.joints.size();
    if (g.num_joints != static_cast<int32_t>(g.joint_names.size()) ||
        g.num_points != static_cast<int32_t>(g.points.size()))
      return refuse("array sizes do not match num_joints / num_points");
    if (g.points.empty()) {
      out.empty = true;
      return out;
    }
    out.index.assign(n, -1);  // controller joint -> goal column
    for (size_t c = 0; c < g.joint_names.size(); ++c) {
      const auto it = std::find(r.joints.begin(), r.joints.end(), g.joint_names[c]);
      if (it == r.joints.end())
        return refuse(fmt::format("joint '{}' is not controlled here (joints: {})", clip(g.joint_names[c]),
                                  fmt::join(r.joints, ", ")));
      if (out.index[it - r.joints.begin()] >= 0)
        return refuse(fmt::format("joint '{}' is listed twice", clip(g.joint_names[c])));
      out.index[it - r.joints.begin()] = static_cast<int>(c);
    }
    if (!r.allow_partial)
      for (size_t k = 0; k < n; ++k)
        if (out.index[k] < 0)
          return refuse(fmt::format("joint '{}' is missing (a goal must name all of: {}; or set "
                                    "allow_partial_joints_goal: true)",
                                    r.joints[k], fmt::join(r.joints, ", ")));
    std::vector<Waypoint> points;
    points.reserve(g.points.size());
    std::string limit_note;
    double prev = 0;
    for (size_t i = 0; i < g.points.size(); ++i) {
      const trajectory_point_t& p = g.points[i];
      if (!std::isfinite(p.time_from_start) || p.time_from_start <= prev)
        return refuse(fmt::format("point {}: time_from_start {} must be greater than {}", i, p.time_from_start, prev));
      prev = p.time_from_start;
      const size_t m = g.joint_names.size();
      if (p.num_positions != static_cast<int32_t>(m) || p.positions.size() != m)
        return refuse(fmt::format("point {}: {} positions for {} joints", i, p.positions.size(), m));
      if (p.num_velocities != static_cast<int32_t>(p.velocities.size()) ||
          p.num_accelerations != static_cast<int32_t>(p.accelerations.size()))
        return refuse(fmt::format("point {}: array sizes do not match num_velocities / num_accelerations", i));
      if (!p.velocities.empty() && p.velocities.size() != m)
        return refuse(fmt::format("point {}: {} velocities for {} joints (give none or one per joint)", i,
                                  p.velocities.size(), m));
      if (!p.accelerations.empty() && (p.accelerations.size() != m || p.velocities.empty()))
        return refuse(fmt::format("point {}: accelerations need velocities and one value per joint", i));
      Waypoint w;
      w.time = p.time_from_start;
      w.pos.reserve(n);
      for (size_t k = 0; k < n; ++k) {
        const int c = out.index[k];
        if (c < 0) {  // left out (allow_partial_joints_goal): holds where the trajectory is (its offset, at start)
          w.pos.push_back(0.0);
          if (!p.velocities.empty()) w.vel.push_back(0.0);
          if (!p.accelerations.empty()) w.acc.push_back(0.0);
          continue;
        }
        const double pos = p.positions[c];
        if (!std::isfinite(pos))
          return refuse(fmt::format("point {}: joint '{}' position is NaN/Inf", i, r.joints[k]));
        const Limit& l = r.limits[k];
        if (l.has && (pos < l.lower || pos > l.upper) && out.beyond++ == 0)
          limit_note = fmt::format("point {} puts joint '{}' at {:g}, beyond its limits [{:g}, {:g}]", i, r.joints[k],
                                   pos, l.lower, l.upper);
        w.pos.push_back(pos);
        if (!p.velocities.empty()) w.vel.push_back(p.velocities[c]);
        if (!p.accelerations.empty()) w.acc.push_back(p.accelerations[c]);
      }
      if (!std::all_of(w.vel.begin(), w.vel.end(), [](double v) { return std::isfinite(v); }) ||
          !std::all_of(w.acc.begin(), w.acc.end(), [](double v) { return std::isfinite(v); }))
        return refuse(fmt::format("point {}: NaN/Inf velocity or acceleration", i));
      points.push_back(std::move(w));
    }
    out.first.assign(n, 0.0);
    for (size_t k = 0; k < n; ++k) out.first[k] = points.front().pos[k];
    out.continuous = r.continuous;
    out.limit_note = std::move(limit_note);
    out.duration = prev;
    out.plan = Trajectory::Plan::make(n, points, r.interpolate);
    return out;
  }

  // Between cycles, in the loop's thread: a prepared goal taken whole (O(joints): the plan started where the
  // trajectory is now; the replaced trajectory freed off the loop).
  void take_goal(PreparedGoal& p) {
    if (!running_) {
      endpoints_->dispose(std::move(p.plan));  // freed off the loop, as a replaced trajectory is
      return reject(p.ids, "the controller is not running");
    }
    if (!p.error.empty()) return reject(p.ids, p.error);
    if (p.empty) return stop(p.ids);
    const size_t n = names_.size();
    std::vector<SplineState> start(n);
    std::vector<double> offset(n, 0.0);
    for (size_t k = 0; k < n; ++k) {
      current_->sample(last_t_, k, start[k]);
      if (p.index[k] < 0) {
        offset[k] = start[k].pos;  // a joint the goal leaves out holds where it is
      } else if (p.continuous[k]) {  // go the short way round to the first point
        offset[k] = -(p.first[k] - (start[k].pos + shortest_angular_distance(start[k].pos, p.first[k])));
      }
    }
    const size_t points = p.plan.points();
    Trajectory next = Trajectory::start(std::move(p.plan), last_t_, start, offset);
    if (goal_active_) {
      std::snprintf(text_, sizeof text_, "replaced by goal %lld", static_cast<long long>(p.ids.goal_id));
      finish(Time{static_cast<int64_t>(last_t_ * 1e6)}, trajectory_status_t::PREEMPTED, text_);
    }
    limit_note_.clear();
    if (p.beyond > 0) {  // as ROS: accepted, and the joint stops at its limit
      limit_note_ = fmt::format(" ({}{}; the joint stops at its limit)", p.limit_note,
                                p.beyond > 1 ? fmt::format(", and {} more positions beyond a limit", p.beyond - 1) : "");
      goal_log_.warn(fmt::format("{}: goal {}: {}{}: accepted as ROS does; the joint stops at its limit", name_,
                                 p.ids.goal_id, p.limit_note,
                                 p.beyond > 1 ? fmt::format(" (and {} more)", p.beyond - 1) : ""));
    }
    std::swap(active_, next);
    endpoints_->dispose(std::move(next));  // the replaced trajectory
    current_ = &active_;
    goal_id_ = p.ids.goal_id;
    goal_active_ = true;
    last_feedback_ = -1e9;
    std::fill(max_path_err_.begin(), max_path_err_.end(), 0.0);
    goal_log_.info(
        fmt::format("{}: goal {} accepted: {} points over {:.3f} s", name_, p.ids.goal_id, points, p.duration));
  }

  Interface iface_;
  std::string name_;
  std::vector<std::string> names_;
  std::vector<JointData*> joints_;        // what it commands: `joints`, or ROS 2's command_joints
  std::vector<const JointData*> states_;  // the state it follows: `joints`'
  std::vector<double> path_tol_, goal_tol_, hold_pos_, max_path_err_, velocity_ff_;
  double goal_time_ = 0, stopped_vel_tol_ = 0.01, monitor_rate_ = 20, state_rate_ = 50, stop_duration_ = 0;
  double last_t_ = 0, last_feedback_ = 0, last_state_ = -1e9;
  bool allow_partial_ = false;
  bool ros2_ = false, open_loop_ = false, interpolate_ = true;
  double cmd_timeout_ = 0;
  std::vector<double> u_min_, u_max_;
  std::vector<Pid> pids_;
  std::vector<SplineState> desired_, rest_from_;
  Trajectory hold_, active_;
  const Trajectory* current_ = nullptr;
  bool goal_active_ = false;
  int64_t goal_id_ = 0;
  trajectory_status_t status_;
  joint_trajectory_controller_state_t state_;
  char text_[512] = {};
  std::string limit_note_;
  Endpoints* endpoints_ = nullptr;
  BusLog bad_log_;   // what the bus sent that could not be a goal: clipped and rate-limited
  BusLog goal_log_;  // goals taken or refused: as many as anyone sends, so clipped and rate-limited too  // appended to the goal's result: a position beyond a limit (set between cycles)
  Publisher<trajectory_status_t> feedback_pub_, result_pub_;
  Publisher<joint_trajectory_controller_state_t> state_pub_;
};

// ROS 2's keys not read here.
std::vector<ParameterInfo> ros2_only_parameters() {
  std::vector<ParameterInfo> v;
  for (const char* key : {"allow_integration_in_goal_trajectories",
                          "allow_nonzero_velocity_at_trajectory_end", "interpolate_from_desired_state",
                          "set_last_command_interface_value_as_state_on_activation", "speed_scaling_topic_name"})
    v.push_back({key, "", "", "", key, "not implemented", false});
  return v;
}

}  // namespace

ControllerType joint_trajectory_controller(Interface command) {
  ControllerTypeInfo t;
  switch (command) {
    case Interface::Position: t.name = "position_controllers/JointTrajectoryController"; break;
    case Interface::Velocity: t.name = "velocity_controllers/JointTrajectoryController"; break;
    case Interface::Effort: t.name = "effort_controllers/JointTrajectoryController"; break;
  }
  t.doc = fmt::format("follows joint_trajectory_t goals through splines on {}", to_string(command));
  t.claims = {command, {"joints"}, "", {}};
  t.command = {"joint_trajectory_t", "command", 0, ""};
  const bool pid = command != Interface::Position;
  const char* with_pid = pid ? "" : "; not used with PositionJointInterface";
  t.parameters = {
      {"joints", "strings", "", "joints", "joints", "the joints a goal must name"},
      {"gains", "map", "", "gains", "gains", std::string("<joint>: {p, i, d, i_clamp}, required") + with_pid},
      {"velocity_ff", "map", "", "velocity_ff", "", std::string("<joint>: factor on the desired velocity") + with_pid},
      {"constraints", "map", "", "constraints", "constraints",
       "goal_time, stopped_velocity_tolerance, <joint>: {trajectory, goal} (0: not checked)"},
      {"state_publish_rate", "number", "50", "state_publish_rate", "state_publish_rate", "Hz of <name>/state (0: never)"},
      {"action_monitor_rate", "number", "20", "action_monitor_rate", "action_monitor_rate", "Hz of <name>/feedback"},
      {"stop_trajectory_duration", "number", "0", "stop_trajectory_duration", "",
       "seconds of the ramp to rest on start, on a path error and on an empty goal"},
      {"allow_partial_joints_goal", "bool", "false", "allow_partial_joints_goal", "allow_partial_joints_goal",
       "goals may leave joints out (they hold)"},
      {"hold_trajectory_duration", "number", "", "hold_trajectory_duration", "", "not implemented", false},
  };
  for (const char* key : {"command_interfaces", "state_interfaces", "open_loop_control", "interpolation_method",
                          "cmd_timeout", "interface_name"})
    t.parameters.push_back({key, "", "", "", key,
                            "ROS 2's; not read by this ROS 1 type (joint_trajectory_controller/JointTrajectoryController "
                            "reads ROS 2's parameters)",
                            false});
  for (const auto& x : ros2_only_parameters()) t.parameters.push_back(x);
  return {t, [command](const std::string&) { return std::make_unique<JointTrajectoryController>(command); }};
}

ControllerType ros2_joint_trajectory_controller() {
  ControllerTypeInfo t;
  t.name = "joint_trajectory_controller/JointTrajectoryController";
  t.ros = RosVersion::Ros2;
  t.doc = "follows joint_trajectory_t goals through splines on the interface command_interfaces names";
  t.claims.joint_params = {"joints", "command_joints"};  // command_joints: the interfaces it writes instead (chaining)
  t.claims.interface_param = "command_interfaces";
  t.command = {"joint_trajectory_t", "command", 0, ""};
  t.parameters = {
      ros2_parameter("joints", "strings", "", "the joints a goal must name"),
      ros2_parameter("command_joints", "strings", "",
                     "what it commands instead, one per joint (chaining: a PID's reference interfaces \"<pid>/<joint>\")"),
      ros2_parameter("command_interfaces", "strings", "",
           "[position], [velocity], [effort]; [position, velocity(, acceleration)], [position, effort] command position"),
      ros2_parameter("state_interfaces", "strings", "[position, velocity]", "position(, velocity(, acceleration)), checked"),
      ros2_parameter("gains", "map", "", "<joint>: {p, i, d, i_clamp, ff_velocity_scale, u_clamp_min/max}, [velocity] and [effort]"),
      ros2_parameter("constraints", "map", "", "goal_time, stopped_velocity_tolerance, <joint>: {trajectory, goal} (0: not checked)"),
      ros2_parameter("state_publish_rate", "number", "50", "Hz of <name>/state (0: never)"),
      ros2_parameter("action_monitor_rate", "number", "20", "Hz of <name>/feedback"),
      ros2_parameter("allow_partial_joints_goal", "bool", "false", "goals may leave joints out (they hold)"),
      ros2_parameter("interpolation_method", "string", "splines", "splines, or none: from waypoint to waypoint"),
      ros2_parameter("cmd_timeout", "number", "0", "s after a trajectory's end: hold the measured position (0: never)"),
      ros2_parameter("open_loop_control", "bool", "false", "[velocity]: the desired velocity as it is, no PID"),
  };
  for (const auto& x : ros2_only_parameters()) t.parameters.push_back(x);
  return {t, [](const std::string&) { return std::make_unique<JointTrajectoryController>(std::nullopt); }};
}

}  // namespace lcm_control::cm
