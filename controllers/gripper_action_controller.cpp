// GripperActionController: one gripper joint to a goal position, control_msgs/GripperCommand's semantics as
// ros_controllers' gripper_action_controller and ros2_controllers' gripper_controllers (Humble, Jazzy) and
// parallel_gripper_controller implement them:
//  position_controllers/GripperActionController             the position command is the goal position
//  effort_controllers/GripperActionController               a PID (`gains/<joint>`) on the position error, with the
//                                                           velocity error as the D input, to an effort clamped to
//                                                           the goal's max_effort
//  parallel_gripper_action_controller/GripperActionController  ROS 2's: as the position one (max_effort 10 by default)
// Goals (gripper_command_t) arrive on `<name>/command`; a new goal preempts the running one. A goal ends SUCCEEDED
// when |goal - position| < goal_tolerance; when the joint moves slower than stall_velocity_threshold for stall_timeout
// short of it, it has stalled: SUCCEEDED with allow_stalling, else ABORTED. The joint keeps being driven to the
// goal after the result (a grasp keeps squeezing). Feedback on `<name>/feedback` at action_monitor_rate, one result
// per goal on `<name>/result` (gripper_status_t). A goal's max_effort <= 0 means the controller's max_effort, and
// that 0 means the URDF's effort limit (ROS would command no effort at all and the gripper would never move).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "control/angles.hpp"
#include "controllers/factories.hpp"
#include "lcm_control/gripper_command_t.hpp"
#include "lcm_control/gripper_status_t.hpp"
#include "rt/log.hpp"

namespace lcm_control::cm {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

class GripperActionController : public Controller {
 public:
  GripperActionController(Interface iface, bool parallel) : iface_(iface), parallel_(parallel) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    name_ = ctx.name();
    const std::string joint = p.string("joint");
    joint_ = ctx.claim(joint, iface_);
    monitor_rate_ = p.number("action_monitor_rate", 20.0);
    if (!(monitor_rate_ > 0)) throw p.error("action_monitor_rate", "must be > 0 (Hz of <name>/feedback)");
    goal_tolerance_ = finite(p, "goal_tolerance", 0.01);
    if (goal_tolerance_ < 0) {  // ROS 1 takes its absolute value
      goal_tolerance_ = -goal_tolerance_;
      ctx.notes.push_back(fmt::format("{}/goal_tolerance: negative; its absolute value {} is used (as ros_controllers "
                                      "does)",
                                      name_, goal_tolerance_));
    }
    max_effort_ = std::abs(finite(p, "max_effort", parallel_ ? 10.0 : 0.0));
    allow_stalling_ = p.boolean("allow_stalling", false);
    stall_velocity_ = std::abs(finite(p, "stall_velocity_threshold", 0.001));
    stall_timeout_ = finite(p, "stall_timeout", 1.0);
    if (stall_timeout_ < 0) throw p.error("stall_timeout", "must be >= 0 seconds");
    if (parallel_) read_state_interfaces(p);

    urdf_effort_ = joint_->urdf && joint_->urdf->effort_limit > 0 ? joint_->urdf->effort_limit : kInf;
    if (iface_ == Interface::Effort) {
      const YAML::Node gains = p.node("gains");
      const std::string where = p.where() + "/gains/" + joint;
      if (!gains || !gains.IsMap() || !gains[joint])
        throw ControllerError(where + ": missing (required for EffortJointInterface): gains: {" + joint +
                              ": {p, i, d, i_clamp}}");
      pid_.set_gains(Params::pid_from(gains[joint], where));
    } else {
      if (p.has("gains")) {
        p.node("gains");
        ctx.notes.push_back(fmt::format("{}/gains: not used with PositionJointInterface (the goal position is the "
                                        "command)",
                                        name_));
      }
      if (max_effort_ > 0 && p.has("max_effort"))
        ctx.notes.push_back(fmt::format("{}/max_effort: {} limits nothing on PositionJointInterface (as in ROS); it "
                                        "is reported in the results. The URDF's effort limit and sim_server's "
                                        "pid_gains set how hard the gripper squeezes",
                                        name_, max_effort_));
    }

    status_.joint = joint;
    status_.message.reserve(512);
    feedback_pub_ = ctx.endpoints().publisher<gripper_status_t>(ctx.channel("feedback"));
    result_pub_ = ctx.endpoints().publisher<gripper_status_t>(ctx.channel("result"));
    ctx.endpoints().subscribe<gripper_command_t>(
        ctx.channel("command"), [this](const gripper_command_t& g) { on_goal(g); },
        [this](const std::string& why) {
          ++dropped_;
          goal_log_.warn(fmt::format("{}: {}", name_, why));
        });
  }

  std::vector<std::string> pid_joints() const override {
    return iface_ == Interface::Effort ? std::vector<std::string>{status_.joint} : std::vector<std::string>{};
  }
  Pid* pid(const std::string& joint) override {
    return iface_ == Interface::Effort && joint == status_.joint ? &pid_ : nullptr;
  }

  void starting(const Time& now) override {
    if (goal_active_) finish(now, gripper_status_t::PREEMPTED, false, false, "controller restarted");
    set_point_ = within_limits(joint_->position);
    limit_ = effort_limit(0);
    pid_.reset();
    if (iface_ == Interface::Effort) joint_->command = 0;
    last_t_ = now.seconds();
  }

  void restart(const Time& now) override {
    if (goal_active_)
      finish(now, gripper_status_t::PREEMPTED, false, false,
             "controller restarted from the current state (hardware restarted, resumed or jumped in time)");
    starting(now);
  }

  void stopping(const Time& now) override {
    if (goal_active_) finish(now, gripper_status_t::PREEMPTED, false, false, "controller stopped");
  }

  void update(const Time& now, double period) override {
    const double t = now.seconds();
    last_t_ = t;
    const double position = joint_->position, velocity = joint_->velocity;
    const double error = joint_->continuous ? shortest_angular_distance(position, set_point_) : set_point_ - position;
    if (iface_ == Interface::Effort) {
      effort_ = std::clamp(pid_.compute(error, -velocity, period), -limit_, limit_);
      joint_->command = effort_;
      joint_->damping = pid_.applied_d();
    } else {
      joint_->command = set_point_;
      effort_ = joint_->effort;
    }
    if (!goal_active_) return;
    if (std::abs(error) < goal_tolerance_) {
      std::snprintf(text_, sizeof text_, "goal %lld reached: position %.6f, error %.6f (goal_tolerance %.6f)",
                    static_cast<long long>(goal_id_), position, error, goal_tolerance_);
      finish(now, gripper_status_t::SUCCEEDED, true, false, text_);
      return;
    }
    if (std::abs(velocity) > stall_velocity_) {
      last_movement_ = t;
    } else if (t - last_movement_ > stall_timeout_) {
      std::snprintf(text_, sizeof text_,
                    "stalled at %.6f, %.6f short of the goal %.6f (goal_tolerance %.6f): slower than "
                    "stall_velocity_threshold %g for %.3f s (stall_timeout %g), effort %.6f%s",
                    position, error, set_point_, goal_tolerance_, stall_velocity_, t - last_movement_, stall_timeout_,
                    effort_, allow_stalling_ ? "; allow_stalling: succeeded" : "; set allow_stalling: true to count a grasp as success");
      finish(now, allow_stalling_ ? gripper_status_t::SUCCEEDED : gripper_status_t::ABORTED, false, true, text_);
      return;
    }
    if (t - last_feedback_ >= 1.0 / monitor_rate_ - 1e-9) {
      last_feedback_ = t;
      fill(now, gripper_status_t::ACTIVE, false, false);
      status_.message.clear();
      feedback_pub_.publish(status_);
    }
  }

 private:
  // A number parameter that must be finite.
  static double finite(Params& p, const std::string& key, double fallback) {
    const double v = p.number(key, fallback);
    if (!std::isfinite(v)) throw p.error(key, "must be a finite number");
    return v;
  }

  // ROS 2's state_interfaces: this controller reads position and velocity, which every joint here has.
  void read_state_interfaces(Params& p) {
    const YAML::Node n = p.node("state_interfaces");
    if (!n) return;
    std::vector<std::string> names;
    try {
      names = n.as<std::vector<std::string>>();
    } catch (const YAML::Exception&) {
      throw p.error("state_interfaces", "expected a list of interface names, e.g. [position, velocity]");
    }
    for (const auto& s : names)
      if (s != "position" && s != "velocity" && s != "effort")
        throw p.error("state_interfaces", fmt::format("'{}' is not a state interface of a joint here (position, "
                                                      "velocity, effort)",
                                                      s));
    for (const char* need : {"position", "velocity"})
      if (std::find(names.begin(), names.end(), need) == names.end())
        throw p.error("state_interfaces", fmt::format("must include {} (the controller checks the goal and stalls "
                                                      "with position and velocity): use [position, velocity]",
                                                      need));
  }

  double within_limits(double x) const {
    const Joint* u = joint_->urdf;
    return u && u->has_position_limits ? std::clamp(x, u->lower, u->upper) : x;
  }

  // The goal's max_effort, else the controller's, else the URDF's; never above the URDF's.
  double effort_limit(double goal_max_effort) const {
    const double asked = goal_max_effort > 0 ? goal_max_effort : max_effort_ > 0 ? max_effort_ : urdf_effort_;
    return std::min(asked, urdf_effort_);
  }

  void fill(const Time& now, int8_t status, bool reached, bool stalled) {
    status_.utime = now.utime;
    status_.goal_id = goal_id_;
    status_.status = status;
    status_.goal_position = set_point_;
    status_.position = joint_->position;
    status_.effort = effort_;
    status_.max_effort = std::isfinite(limit_) ? limit_ : 0.0;
    status_.reached_goal = reached;
    status_.stalled = stalled;
  }

  void finish(const Time& now, int8_t status, bool reached, bool stalled, const char* message) {
    fill(now, status, reached, stalled);
    status_.message.assign(message);
    result_pub_.publish(status_);
    goal_active_ = false;
  }

  void reject(const gripper_command_t& g, const std::string& why) {
    gripper_status_t r{};
    r.utime = g.utime;
    r.goal_id = g.goal_id;
    r.status = gripper_status_t::REJECTED;
    r.joint = status_.joint;
    r.goal_position = g.position;
    r.position = joint_->position;
    r.message = fmt::format("{}: goal {} rejected: {}", name_, g.goal_id, why);
    result_pub_.publish(r);
    goal_log_.warn(r.message);
  }

  // Runs between cycles, in the loop's thread.
  void on_goal(const gripper_command_t& g) {
    if (!running_) return reject(g, fmt::format("the controller is not running (start it: cmctl start {})", name_));
    if (!std::isfinite(g.position) || !std::isfinite(g.max_effort)) {
      ++dropped_;
      return reject(g, fmt::format("position {} or max_effort {} is NaN/Inf", g.position, g.max_effort));
    }
    const Joint* u = joint_->urdf;
    if (u && u->has_position_limits && (g.position < u->lower || g.position > u->upper))
      return reject(g, fmt::format("position {} is outside the limits [{}, {}] of joint '{}' (URDF)", g.position,
                                   u->lower, u->upper, status_.joint));
    const Time now{static_cast<int64_t>(std::llround(last_t_ * 1e6))};
    if (goal_active_) {
      std::snprintf(text_, sizeof text_, "replaced by goal %lld", static_cast<long long>(g.goal_id));
      finish(now, gripper_status_t::PREEMPTED, false, false, text_);
    }
    set_point_ = g.position;
    limit_ = effort_limit(g.max_effort);
    goal_id_ = g.goal_id;
    goal_active_ = true;
    last_movement_ = last_t_;
    last_feedback_ = -kInf;
    goal_log_.info(fmt::format("{}: goal {} accepted: position {} on '{}', max_effort {}", name_, g.goal_id,
                               g.position, status_.joint, limit_));
  }

  Interface iface_;
  bool parallel_;
  std::string name_;
  JointData* joint_ = nullptr;
  Pid pid_;
  double monitor_rate_ = 20, goal_tolerance_ = 0.01, max_effort_ = 0, stall_velocity_ = 0.001, stall_timeout_ = 1;
  bool allow_stalling_ = false;
  double urdf_effort_ = kInf, limit_ = kInf, set_point_ = 0, effort_ = 0;
  double last_t_ = 0, last_movement_ = 0, last_feedback_ = -kInf;
  bool goal_active_ = false;
  int64_t goal_id_ = 0;
  gripper_status_t status_{};
  char text_[512] = {};
  BusLog goal_log_;  // goals and what could not be one: as many as anyone sends, so clipped and rate-limited
  Publisher<gripper_status_t> feedback_pub_, result_pub_;
};

}  // namespace

ControllerType gripper_action_controller(Interface command, bool parallel) {
  if (parallel && command != Interface::Position)
    throw std::invalid_argument("gripper_action_controller: the parallel gripper takes a position interface");
  if (command == Interface::Velocity)
    throw std::invalid_argument("gripper_action_controller: no velocity_controllers/GripperActionController");
  ControllerTypeInfo t;
  const bool effort = command == Interface::Effort;
  if (parallel) {
    t.name = "parallel_gripper_action_controller/GripperActionController";
    t.ros = RosVersion::Ros2;
  } else {
    t.name = effort ? "effort_controllers/GripperActionController" : "position_controllers/GripperActionController";
    t.ros = RosVersion::Both;  // gripper_controllers (Humble, Jazzy) registers the ROS 1 names
  }
  t.doc = effort ? "a gripper_command_t goal on `joint` through a PID to an effort clamped to its max_effort; "
                   "results on <name>/result"
                 : "a gripper_command_t goal on `joint` as its position command; results on <name>/result";
  t.claims = {command, {"joint"}, "", {}};
  t.command = {"gripper_command_t", "command", 0, ""};
  const char* d_effort = parallel ? "10" : "0";
  t.parameters = {
      {"joint", "string", "", "joint", "joint", "the gripper joint"},
      {"goal_tolerance", "number", "0.01", "goal_tolerance", "goal_tolerance",
       "a goal succeeds when |goal - position| is below it"},
      {"max_effort", "number", d_effort, "max_effort", "max_effort",
       effort ? "effort limit for goals whose max_effort is 0 (0: the URDF's)"
              : "reported only: a position interface limits no effort"},
      {"allow_stalling", "bool", "false", "", "allow_stalling",
       "a stall short of the goal SUCCEEDS (a grasp) instead of ABORTED"},
      {"stall_velocity_threshold", "number", "0.001", "stall_velocity_threshold", "stall_velocity_threshold",
       "below this speed the gripper is not moving"},
      {"stall_timeout", "number", "1", "stall_timeout", "stall_timeout",
       "seconds not moving short of the goal before it has stalled"},
      {"action_monitor_rate", "number", "20", "action_monitor_rate", "action_monitor_rate", "Hz of <name>/feedback"},
  };
  if (effort)
    t.parameters.push_back({"gains", "map", "", "gains", "gains", "<joint>: {p, i, d, i_clamp}, required"});
  else
    t.parameters.push_back({"gains", "map", "", "", "", "not used: the goal position is the command"});
  if (parallel) {
    t.parameters.push_back({"state_interfaces", "strings", "[position, velocity]", "", "state_interfaces",
                            "must include position and velocity"});
    t.parameters.push_back({"max_effort_interface", "string", "", "", "max_effort_interface",
                            "not implemented (no max_effort command interface here)", false});
    t.parameters.push_back({"max_velocity", "number", "", "", "max_velocity",
                            "not implemented (no max_velocity command interface here)", false});
    t.parameters.push_back({"max_velocity_interface", "string", "", "", "max_velocity_interface",
                            "not implemented (no max_velocity command interface here)", false});
  }
  if (parallel)
    for (auto& p : t.parameters) p.ros1.clear();  // a ROS 2 type only
  return {t, [command, parallel](const std::string&) {
            return std::make_unique<GripperActionController>(command, parallel);
          }};
}

}  // namespace lcm_control::cm
