// send-trajectory: one trajectory goal to a JointTrajectoryController (what
// rqt_joint_trajectory_controller or a FollowJointTrajectory client does in
// ROS), from --point arguments, a YAML or a CSV file; waits for the result:
// exit 0 on SUCCEEDED, 1 with the controller's reason, 4 without a result.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <optional>
#include <set>

#include "cli/cli.hpp"
#include "description/input_file.hpp"
#include "bus/messages.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/cm_views.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/clients/goal_watch.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/clients/trajectory_goal.hpp"

namespace lcm_control::tools {
namespace {

struct Options {
  std::string target, joints, file, csv;
  std::vector<std::string> points;
  bool relative = false, no_wait = false, verbose = false;
  double result_timeout = 0, timeout = 3;
};

// No result (or no joint_states) in time: exit code kExitBus, as for every unanswered request.
class NoAnswer : public BusError {
 public:
  using BusError::BusError;
};

// --relative: the goal joints' positions from the first valid joint_states message.
// Meanwhile every channel on the bus is noted, for the error when none comes.
class CurrentPositions {
 public:
  explicit CurrentPositions(Bus& bus) : bus_(bus), channel_(bus.channel(channels::kJointStates)) {
    states_ = subscribe_guarded<&CurrentPositions::on_state>(bus, channel_, this);
    any_ = bus.subscribe(".*", &CurrentPositions::on_any, this);
  }
  ~CurrentPositions() {
    bus_.unsubscribe(states_);
    bus_.unsubscribe(any_);
  }
  CurrentPositions(const CurrentPositions&) = delete;
  CurrentPositions& operator=(const CurrentPositions&) = delete;

  // `listed`: the controller manager's controllers, to say whether a JointStateController runs.
  std::vector<double> of(const std::vector<std::string>& joints, double timeout_s,
                         const std::vector<controller_info_t>& listed) {
    if (!pump_until(bus_, [&] { return state_.has_value(); }, timeout_s)) {
      if (stop_requested()) throw std::runtime_error("interrupted while waiting for joint_states");
      seen_.erase("LCM_SELF_TEST");
      seen_.erase(channel_);
      std::string publisher;
      for (const auto& c : listed)
        if (std::find(c.publishes.begin(), c.publishes.end(), channels::kJointStates) != c.publishes.end() &&
            c.state == "running")
          publisher = c.name;
      throw NoAnswer(fmt::format(
          "--relative needs the current positions, but no valid joint_state_t came on '{}' within {}{} ({}); {}",
          channel_, seconds_text(timeout_s), invalid_.empty() ? "" : ", only invalid ones: " + invalid_,
          seen_.empty() ? "no other channel either" : fmt::format("channels seen: {}", fmt::join(seen_, ", ")),
          publisher.empty()
              ? std::string("no JointStateController runs in the controller manager: start one (spawner "
                            "joint_state_controller)")
              : fmt::format("the controller manager runs '{}', so its time does not advance: is sim_server running "
                            "and stepping?",
                            publisher)));
    }
    std::vector<double> out;
    for (const auto& j : joints) {
      const auto it = std::find(state_->name.begin(), state_->name.end(), j);
      if (it == state_->name.end())
        throw std::runtime_error(fmt::format("--relative: joint '{}' is not in '{}' (it has: {})", j, channel_,
                                             fmt::join(state_->name, ", ")));
      out.push_back(state_->position[size_t(it - state_->name.begin())]);
    }
    return out;
  }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const joint_state_t* m) {
    if (state_) return;
    const std::string bad = check(*m);
    if (bad.empty())
      state_ = *m;
    else
      invalid_ = bad;
  }
  void on_any(const lcm::ReceiveBuffer*, const std::string& channel) {
    if (seen_.size() < 40) seen_.insert(channel);
  }

  Bus& bus_;
  std::string channel_, invalid_;
  int states_ = 0, any_ = 0;
  std::optional<joint_state_t> state_;
  std::set<std::string> seen_;
};

TrajectoryGoal read_goal(const Options& o) {
  if (!o.file.empty()) return parse_goal_yaml(read_input_file(o.file, "trajectory YAML", "--file"), o.file);
  if (!o.csv.empty()) return parse_goal_csv(read_input_file(o.csv, "trajectory CSV", "--csv"), o.csv);
  return parse_point_args(o.points);
}

int run(const Options& o, const BusFlags& bus_flags) {
  const std::string controller = controller_name(o.target);
  if (controller.empty())
    throw std::runtime_error("CONTROLLER is empty: give the controller's name, e.g. arm_controller");
  TrajectoryGoal goal = read_goal(o);
  if (!o.joints.empty()) set_joints_from_flag(goal, o.joints);
  if (!goal.joints.empty()) check_goal(goal);

  install_stop_signals();
  Bus bus(bus_flags.lcm_url, bus_flags.ns);  // LCM's receive thread: a short-lived tool waiting for answers
  CmClient cm(bus, "send-trajectory");
  const std::vector<controller_info_t> listed = cm.list(o.timeout).controllers;
  const controller_info_t info = trajectory_controller(listed, controller, bus.channel(""));
  if (goal.joints.empty()) {
    for (const std::string& j : info.joints) goal.joints.push_back(joint_behind(listed, j));
    goal.joints_where = fmt::format("the joints of '{}'", controller);
    if (goal.joints != info.joints) goal.joints_where += " (the joints its command_joints chain to)";
    check_goal(goal);
  }
  if (o.relative) {
    const std::vector<double> start = CurrentPositions(bus).of(goal.joints, o.timeout, listed);
    add_offsets(goal, start);
    if (o.verbose) {
      std::vector<std::string> at;
      for (size_t k = 0; k < start.size(); ++k) at.push_back(fmt::format("{} {:.6f}", goal.joints[k], start[k]));
      fmt::print("start ({}): {}\n", bus.channel(channels::kJointStates), fmt::join(at, ", "));
    }
  }

  const int64_t goal_id = new_request_id();
  GoalWatch<trajectory_status_t> watch(bus, controller, goal_id, o.verbose, [](const trajectory_status_t& m) {
    std::vector<std::string> joints;
    for (size_t k = 0; k < m.joint_names.size() && k < m.error.size(); ++k)
      joints.push_back(fmt::format("{} desired {:.6f} actual {:.6f} error {:.6f}", m.joint_names[k], m.desired[k],
                                   m.actual[k], m.error[k]));
    return fmt::format("{}", fmt::join(joints, "; "));
  });  // listening before the goal goes out
  const double span = goal.points.back().time;
  const double timeout = o.result_timeout > 0 ? o.result_timeout : span + 10.0;
  const std::string command = bus.channel(controller + "/command");
  bus.publish(controller + "/command", to_message(goal, goal_id, wall_us()));
  if (o.no_wait || o.verbose)
    fmt::print("sent goal {} on '{}': {} point{} over {:g} s for {}{}\n", goal_id, command, goal.points.size(),
               goal.points.size() == 1 ? "" : "s", span, fmt::join(goal.joints, ", "),
               o.no_wait ? "" : fmt::format("; waiting up to {} for the result", seconds_text(timeout)));
  if (o.no_wait) return kExitOk;
  std::fflush(stdout);

  pump_until(bus, [&] { return watch.result().has_value(); }, timeout);
  if (const auto& r = watch.result()) {
    const std::string message = without_controller_prefix(r->message, controller);
    if (r->status != trajectory_status_t::SUCCEEDED)
      throw std::runtime_error(goal_failure(cm, controller, status_name(r->status), message));
    fmt::print("{}: SUCCEEDED: {}\n", controller, message);
    return kExitOk;
  }
  if (stop_requested()) {  // Ctrl-C: stop the robot as cancelling a ROS goal does (an empty trajectory)
    const int sig = clear_stop();
    TrajectoryGoal stop;
    stop.joints = goal.joints;
    bus.publish(controller + "/command", to_message(stop, new_request_id(), wall_us()));
    pump_until(bus, [&] { return watch.result().has_value(); }, 1.0);
    const auto& r = watch.result();
    fmt::print(stderr, "send-trajectory: interrupted: sent an empty trajectory to stop '{}' (goal {}: {})\n",
               controller, goal_id,
               r ? status_name(r->status) + ": " + without_controller_prefix(r->message, controller) : std::string("no result yet"));
    return 128 + sig;
  }
  throw NoAnswer(no_goal_result(cm, bus, controller, timeout, watch.feedback(), "give a longer --result-timeout"));
}

}  // namespace
}  // namespace lcm_control::tools

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Send one trajectory to a JointTrajectoryController and wait for its result (rqt_joint_trajectory_controller, "
      "or `rostopic pub CONTROLLER/command trajectory_msgs/JointTrajectory` with the result of the action). Waypoints "
      "come from --point (repeatable), --file (YAML) or --csv; times are seconds from the start of the goal.\n"
      "Examples:\n"
      "  send-trajectory arm_controller --joints a,b,c --point 2:0.1,0.2,0.3 --point 4:0,0,0\n"
      "  send-trajectory arm_controller --point 2:0.1,0.2,0.3:0,0,0     # TIME:POSITIONS:VELOCITIES\n"
      "  send-trajectory /arm_controller/command --file goal.yaml       # joint_names, points (JointTrajectory)\n"
      "  send-trajectory arm_controller --csv goal.csv                  # header time,a,b,c; a row per point\n"
      "  send-trajectory arm_controller --relative --point 1:0.1,0,0    # offsets from joint_states\n"
      "Without --joints (or joint names in the file) the controller's joints are used, in the order `cmctl list` "
      "shows. Exit codes: 0 SUCCEEDED (one line on stdout), 1 any other result (status and the controller's reason on "
      "stderr) or a controller that is not a running JointTrajectoryController, 2 usage, 3 bad waypoints, 4 no answer "
      "(no result within --result-timeout, no controller manager, no joint_states), 130 Ctrl-C (the controller is sent an "
      "empty trajectory, which stops it).",
      "send-trajectory"};
  Options o;
  BusFlags bus_flags;
  app.add_option("CONTROLLER", o.target, "the JointTrajectoryController (ROS's /NAME and /NAME/command work too)")
      ->required();
  app.add_option("--joints", o.joints, "comma-separated joint names (default: the file's, else the controller's)");
  app.add_option("--point", o.points,
                 "TIME:POSITIONS[:VELOCITIES], lists comma-separated, e.g. 2:0.1,0.2 (repeatable, in time order)")
      ->allow_extra_args(false);  // one value per --point: CONTROLLER may follow
  app.add_option("--file", o.file, "YAML: joint_names: [...], points: [{positions: [...], velocities: [...], "
                                   "time_from_start: 2.0 or {secs: 2, nsecs: 0}}]");
  app.add_option("--csv", o.csv, "CSV: header time,<joint>,...; one row per point");
  app.add_flag("--relative", o.relative, "positions are offsets from the current ones (the first joint_states)");
  app.add_option("--result-timeout", o.result_timeout,
                 "seconds to wait for the result (default: the last point's time + 10)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--no-wait", o.no_wait, "send the goal and exit");
  app.add_flag("-v,--verbose", o.verbose, "print the goal sent and the controller's feedback while it runs");
  app.add_option("--timeout", o.timeout,
                 "seconds to wait for the controller manager's answer and, with --relative, for joint_states")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&] {
    const int sources = int(!o.points.empty()) + int(!o.file.empty()) + int(!o.csv.empty());
    if (sources != 1) {
      fmt::print(stderr, "send-trajectory: error: {}: --point TIME:POSITIONS (repeatable), --file goal.yaml or --csv "
                         "goal.csv\n",
                 sources == 0 ? "give the waypoints with one of" : "give the waypoints with only one of");
      return int(kExitUsage);
    }
    return run(o, bus_flags);
  });
}
