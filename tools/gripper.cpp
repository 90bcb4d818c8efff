// gripper: one goal to a GripperActionController (what a control_msgs/GripperCommand action client does in ROS:
// rqt's action client, MoveIt's gripper controller handle); waits for the result: exit 0 on SUCCEEDED, 1 with the
// controller's reason on anything else, 4 without a result.
#include <fmt/format.h>

#include <cmath>
#include <optional>

#include "cli/cli.hpp"
#include "lcm_control/gripper_command_t.hpp"
#include "lcm_control/gripper_status_t.hpp"
#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/clients/goal_watch.hpp"
#include "tools/lib/clients/gripper_goal.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/clients/trajectory_goal.hpp"

namespace lcm_control::tools {
namespace {

struct Options {
  std::string target;
  double position = NAN, max_effort = 0, timeout = 10, cm_timeout = 3;
  bool verbose = false;
};

// No result (or no controller manager) in time: exit code kExitBus, as for every unanswered request.
class NoAnswer : public BusError {
 public:
  using BusError::BusError;
};

int run(const Options& o, const BusFlags& bus_flags) {
  const std::string controller = controller_name(o.target);
  if (controller.empty())
    throw std::runtime_error("CONTROLLER is empty: give the controller's name, e.g. gripper_controller");
  install_stop_signals();
  Bus bus(bus_flags.lcm_url, bus_flags.ns);  // LCM's receive thread: a short-lived tool waiting for answers
  CmClient cm(bus, "gripper");
  gripper_controller(cm.list(o.cm_timeout).controllers, controller, bus.channel(""));

  const int64_t goal_id = new_request_id();
  GoalWatch<gripper_status_t> watch(bus, controller, goal_id, o.verbose, [](const gripper_status_t& m) {
    return fmt::format("{} position {:.6f} (goal {:.6f}) effort {:.6f}", m.joint, m.position, m.goal_position, m.effort);
  });  // listening before the goal goes out
  gripper_command_t goal{};
  goal.utime = wall_us();
  goal.goal_id = goal_id;
  goal.position = o.position;
  goal.max_effort = o.max_effort;
  bus.publish(controller + "/command", goal);
  if (o.verbose)
    fmt::print("sent goal {} on '{}': position {:g}, max_effort {:g}; waiting up to {} for the result\n", goal_id,
               bus.channel(controller + "/command"), o.position, o.max_effort, seconds_text(o.timeout));
  std::fflush(stdout);

  pump_until(bus, [&] { return watch.result().has_value(); }, o.timeout);
  if (const auto& r = watch.result()) {
    const std::string message = without_controller_prefix(r->message, controller);
    const std::string figures = fmt::format("{}: position {:.6f}, effort {:.6f}{}{}", r->joint, r->position, r->effort,
                                            r->stalled ? ", stalled" : "", r->reached_goal ? ", reached goal" : "");
    if (r->status != gripper_status_t::SUCCEEDED)
      throw std::runtime_error(
          goal_failure(cm, controller, gripper_status_name(r->status), fmt::format("{} ({})", message, figures)));
    fmt::print("{}: SUCCEEDED: {} ({})\n", controller, message, figures);
    return kExitOk;
  }
  if (stop_requested()) {
    const int sig = clear_stop();
    fmt::print(stderr,
               "gripper: interrupted: goal {} keeps running in '{}' (send another goal to change it)\n", goal_id,
               controller);
    return 128 + sig;
  }
  throw NoAnswer(no_goal_result(cm, bus, controller, o.timeout, watch.feedback(),
                                "(still moving, or stall_timeout is longer); give a longer --timeout"));
}

}  // namespace
}  // namespace lcm_control::tools

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Send one goal to a GripperActionController and wait for its result (a control_msgs/GripperCommand action "
      "client: rqt, MoveIt's gripper handle). The gripper joint goes to --position; the goal ends SUCCEEDED within "
      "the controller's goal_tolerance, or when it stalls (a grasp) with allow_stalling; ABORTED when it stalls "
      "without; PREEMPTED when another goal replaces it.\n"
      "Examples:\n"
      "  gripper gripper_controller --position 0.02\n"
      "  gripper gripper_controller --position 0.05 --max-effort 20 --timeout 5\n"
      "Exit codes: 0 SUCCEEDED (one line on stdout), 1 any other result (status and the controller's reason on "
      "stderr) or a controller that is not a running GripperActionController, 2 usage, 4 no answer (no result within "
      "--timeout, no controller manager), 130 Ctrl-C (the goal keeps running).",
      "gripper"};
  Options o;
  BusFlags bus_flags;
  app.add_option("CONTROLLER", o.target, "the GripperActionController (ROS's /NAME and /NAME/command work too)")
      ->required();
  app.add_option("--position", o.position, "where the gripper joint goes (m or rad, within its URDF limits)")
      ->required();
  app.add_option("--max-effort", o.max_effort,
                 "effort limit of an effort_controllers/GripperActionController (N or N*m; 0: the controller's "
                 "max_effort, else the URDF's limit); a position interface only reports it")
      ->capture_default_str();
  app.add_option("--timeout,--result-timeout", o.timeout,
                 "seconds to wait for the result (--result-timeout as send-trajectory names it)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--cm-timeout", o.cm_timeout, "seconds to wait for the controller manager's answer")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("-v,--verbose", o.verbose, "print the goal sent and the controller's feedback while it runs");
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&] {
    if (!std::isfinite(o.position) || !std::isfinite(o.max_effort)) {
      fmt::print(stderr, "gripper: error: --position and --max-effort must be finite numbers\n");
      return int(kExitUsage);
    }
    return run(o, bus_flags);
  });
}
