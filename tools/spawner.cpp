// spawner: the controller_manager spawner. Loads controllers, starts them in
// one strict switch, stays running, and stops and unloads them on Ctrl-C. One
// that fails is named with its reason, the others run, and the exit is non-zero.
#include <algorithm>

#include "cli/cli.hpp"
#include "tools/lib/cm_client.hpp"
#include "tools/lib/spawn.hpp"
#include "tools/lib/support.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Load controllers and start them all in one strict switch (ROS's controller_manager spawner), then stay running; "
      "on Ctrl-C or SIGTERM stop and unload them. A controller that fails to load or start is named with the reason "
      "and the others run, as with ROS's spawner; the ready line names it ('; failed: NAME') and the exit status is "
      "then 1. If none can be spawned (or with --activate-as-group, any), it exits 1 at once with nothing left "
      "loaded. Unlike ROS's, every wait is bounded.\n"
      "Examples:\n"
      "  spawner joint_state_controller j1_controller j2_controller\n"
      "  spawner j2_effort_controller --stopped      # load only; start later with cmctl start\n"
      "  spawner arm_controller --inactive -c /robot1/controller_manager   # ROS 2's flags",
      "spawner"};
  std::vector<std::string> names;
  SpawnOptions o;
  double shutdown_timeout = 1.5;
  bool hardware_later = false;
  BusFlags bus_flags;
  app.add_option("NAME", names, "controllers (top-level keys of the ros_control YAML)");
  app.add_option("--load-inactive", o.inactive,
                 "also load these, never starting them (a ROS 2 launch's `spawner --inactive` calls)");
  app.add_flag("--stopped,--inactive,--load-only", o.stopped, "load only, do not start (ROS 2: --inactive)");
  app.add_option("--timeout,--controller-manager-timeout", o.timeout_s,
                 "seconds to wait for the controller manager and for each answer")
      ->check(CLI::PositiveNumber);
  std::string manager, param_file;
  app.add_option("-c,--controller-manager", manager,
                 "ROS 2: the controller manager's node name (/NS/controller_manager): its namespace is --namespace");
  app.add_option("-p,--param-file", param_file,
                 "ROS 2: the controllers' parameter file; here the controller manager reads them from its --config");
  app.add_flag("--activate-as-group", o.as_group,
               "all or nothing (ROS 2): if one controller fails to load or start, none is left loaded and the "
               "spawner exits 1");
  app.add_flag("--unload-on-kill,-u", "ROS 2's flag, accepted: this spawner always unloads its controllers when "
               "stopped");
  app.add_option("--shutdown-timeout", shutdown_timeout, "seconds for stopping and unloading at exit")
      ->check(CLI::PositiveNumber);
  // launch in lockstep starts the simulator after the spawner: no warning about its missing state then.
  app.add_flag("--hardware-later", hardware_later, "do not warn when no hardware state has arrived yet")->group("");
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&] {
    install_stop_signals();
    if (!manager.empty()) {
      const std::string ns = ros2_manager_namespace(manager);
      if (!bus_flags.ns.empty() && ns != bus_flags.ns)
        throw std::runtime_error(fmt::format("--controller-manager {} is in namespace '{}' but --namespace is '{}'; "
                                             "give one of them",
                                             manager, ns, bus_flags.ns));
      bus_flags.ns = ns;
    }
    if (!param_file.empty())
      fmt::print(stderr, "spawner: note: --param-file {}: the controller manager reads the parameters from its own "
                         "--config (give it that file)\n", param_file);
    o.say = [](const std::string& line) { fmt::print(stderr, "spawner: {}\n", line); };
    if (names.empty() && o.inactive.empty())
      throw CLI::ValidationError("NAME", "name the controllers to spawn (or --load-inactive NAME)");
    Spawner spawner(names, o);
    {
      Bus bus(bus_flags.lcm_url, bus_flags.ns);
      CmClient cm(bus, "spawner");
      spawner.spawn(cm);
      if (!o.stopped && !hardware_later) {
        const cm_response_t listed = cm.list(o.timeout_s);
        if (listed.hardware_age_us < 0)
          o.say(fmt::format("warning: the controllers run, but the controller manager reports {}", listed.hardware));
      }
    }
    // Idle without an LCM socket: a udpm socket receives every message on the
    // bus, which costs CPU the simulation could use.
    std::vector<std::string> failed, inactive;
    for (const auto& [n, why] : spawner.failed()) failed.push_back(n);
    for (const auto& n : o.inactive)
      if (std::find(failed.begin(), failed.end(), n) == failed.end()) inactive.push_back(n);
    const std::vector<std::string> up = o.stopped ? spawner.loaded() : spawner.running();
    // launch reads this line: "ready: ", then "; failed: A, B" when some could not be spawned.
    fmt::print(stderr, "spawner: ready: {} {}{}{} (Ctrl-C to stop and unload)\n",
               up.empty() ? "no controllers" : fmt::format("{}", fmt::join(up, ", ")),
               o.stopped ? "loaded" : "running",
               inactive.empty() ? "" : fmt::format("; {} loaded, inactive", fmt::join(inactive, ", ")),
               failed.empty() ? "" : fmt::format("; failed: {}", fmt::join(failed, ", ")));
    while (!stop_requested()) sleep_until_us(monotonic_us() + 1000000);
    clear_stop();
    Bus bus(bus_flags.lcm_url, bus_flags.ns);
    CmClient cm(bus, "spawner");
    const bool ok = spawner.teardown(cm, shutdown_timeout);
    fmt::print(stderr, "spawner: {}\n", ok ? "stopped and unloaded, bye" : "exiting without a clean unload");
    if (!spawner.failed().empty()) {
      for (const auto& [n, why] : spawner.failed()) fmt::print(stderr, "spawner: error: controller '{}' {}\n", n, why);
      return int(kExitFailure);
    }
    return int(kExitOk);
  });
}
