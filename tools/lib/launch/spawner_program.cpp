#include "tools/lib/launch/spawner_program.hpp"

#include <fmt/ranges.h>

#include <algorithm>

#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/wait.hpp"

namespace lcm_control::tools {

void add_spawner_flags(CLI::App& app, SpawnerFlags& f) {
  app.add_option("NAME", f.names, "controllers (top-level keys of the ros_control YAML)");
  app.add_option("--load-inactive", f.o.inactive,
                 "also load these, never starting them (a ROS 2 launch's `spawner --inactive` calls)");
  app.add_flag("--stopped,--inactive,--load-only", f.o.stopped, "load only, do not start (ROS 2: --inactive)");
  app.add_option("--timeout,--controller-manager-timeout", f.o.timeout_s,
                 "seconds to wait for the controller manager and for each answer")
      ->check(CLI::PositiveNumber);
  app.add_option("-c,--controller-manager", f.manager,
                 "ROS 2: the controller manager's node name (/NS/controller_manager): its namespace is --namespace");
  app.add_option("-p,--param-file", f.param_file,
                 "ROS 2: the controllers' parameter file; here the controller manager reads them from its --config");
  app.add_flag("--activate-as-group", f.o.as_group,
               "all or nothing (ROS 2): if one controller fails to load or start, none is left loaded and the "
               "spawner exits 1");
  app.add_flag("--unload-on-kill,-u", "ROS 2's flag, accepted: this spawner always unloads its controllers when "
               "stopped");
  app.add_option("--shutdown-timeout", f.shutdown_timeout, "seconds for stopping and unloading at exit")
      ->check(CLI::PositiveNumber);
  // launch in lockstep starts the simulator after the spawner: no warning about its missing state then.
  app.add_flag("--hardware-later", f.hardware_later, "do not warn when no hardware state has arrived yet")->group("");
  add_bus_flags(app, f.bus);
}

int run_spawner(SpawnerFlags f) {
  install_stop_signals();
  if (!f.manager.empty()) {
    const std::string ns = ros2_manager_namespace(f.manager);
    if (!f.bus.ns.empty() && ns != f.bus.ns)
      throw std::runtime_error(fmt::format("--controller-manager {} is in namespace '{}' but --namespace is '{}'; "
                                           "give one of them",
                                           f.manager, ns, f.bus.ns));
    f.bus.ns = ns;
  }
  if (!f.param_file.empty())
    fmt::print(stderr, "spawner: note: --param-file {}: the controller manager reads the parameters from its own "
                       "--config (give it that file)\n", f.param_file);
  f.o.say = [](const std::string& line) { fmt::print(stderr, "spawner: {}\n", line); };
  if (f.names.empty() && f.o.inactive.empty())
    throw CLI::ValidationError("NAME", "name the controllers to spawn (or --load-inactive NAME)");
  Spawner spawner(f.names, f.o);
  {
    Bus bus(f.bus.lcm_url, f.bus.ns);
    CmClient cm(bus, "spawner");
    spawner.spawn(cm);
    if (!f.o.stopped && !f.hardware_later) {
      const cm_response_t listed = cm.list(f.o.timeout_s);
      if (listed.hardware_age_us < 0)
        f.o.say(fmt::format("warning: the controllers run, but the controller manager reports {}", listed.hardware));
    }
  }
  // Idle without an LCM socket: a udpm socket receives every message on the
  // bus, which costs CPU the simulation could use.
  std::vector<std::string> failed, inactive;
  for (const auto& [n, why] : spawner.failed()) failed.push_back(n);
  for (const auto& n : f.o.inactive)
    if (std::find(failed.begin(), failed.end(), n) == failed.end()) inactive.push_back(n);
  const std::vector<std::string> up = f.o.stopped ? spawner.loaded() : spawner.running();
  // launch reads this line: "ready: ", then "; failed: A, B" when some could not be spawned.
  fmt::print(stderr, "spawner: ready: {} {}{}{} (Ctrl-C to stop and unload)\n",
             up.empty() ? "no controllers" : fmt::format("{}", fmt::join(up, ", ")),
             f.o.stopped ? "loaded" : "running",
             inactive.empty() ? "" : fmt::format("; {} loaded, inactive", fmt::join(inactive, ", ")),
             failed.empty() ? "" : fmt::format("; failed: {}", fmt::join(failed, ", ")));
  while (!stop_requested()) sleep_until_us(monotonic_us() + 1000000);
  clear_stop();
  Bus bus(f.bus.lcm_url, f.bus.ns);
  CmClient cm(bus, "spawner");
  const bool ok = spawner.teardown(cm, f.shutdown_timeout);
  fmt::print(stderr, "spawner: {}\n", ok ? "stopped and unloaded, bye" : "exiting without a clean unload");
  if (!spawner.failed().empty()) {
    for (const auto& [n, why] : spawner.failed()) fmt::print(stderr, "spawner: error: controller '{}' {}\n", n, why);
    return int(kExitFailure);
  }
  return int(kExitOk);
}

}  // namespace lcm_control::tools
