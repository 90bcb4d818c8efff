#include "controller_manager/program.hpp"

#include <sched.h>

#include <algorithm>
#include <future>
#include <limits>

#include "controller_manager/manager.hpp"
#include "controller_manager/plugins.hpp"
#include "controller_manager/services.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"
#include "rt/log.hpp"
#include "rt/stop_signal.hpp"

namespace lcm_control::cm {

void add_program_flags(CLI::App& app, ProgramFlags& f) {
  add_robot_process_flags(app, f.robot,
                          "robot URDF (or .urdf.xacro: --xacro-arg gives its arguments) with <transmission> tags",
                          "ros_control YAML (controllers as top-level keys) or ROS 2 parameter file; none: the URDF's "
                          "gz_ros2_control plugin <parameters>");
  app.add_option("--silence-timeout", f.silence_s,
                 "seconds without hardware/state after which controllers are not updated and switches apply at once")
      ->check(CLI::PositiveNumber);
  app.add_option("--spin-us", f.spin_us,
                 "real time: sleep to this long before each expected hardware/state, then poll without sleeping up "
                 "to this long after it, so that the state is taken as it arrives instead of a wake-up later (costs "
                 "about this much CPU per period; sim_server has the same flag for its deadlines). The poll yields the "
                 "CPU to anything else ready on it: on a loaded machine use it with --rt-priority")
      ->check(CLI::Range(int64_t{0}, int64_t{100000}));
  app.add_flag("--quiet-model", f.quiet_model,
               "do not print the robot model's notes and warnings: launch gives it when it starts sim_server on the "
               "same files, which prints the same ones (each warning once per cause, not once per process)");
}

int run_controller_manager(const ProgramFlags& f) {
  std::string scheduling = apply_scheduling(f.robot.sched);
  map_large_allocations_apart();
  if (f.spin_us > 0) {
    set_timer_slack(1000);  // the sleep before each spin must not end late by the default 50 us
    scheduling += fmt::format("{}spinning {} us around each real-time state", scheduling.empty() ? "" : ", ", f.spin_us);
  }
  setup_logging("controller_manager", f.robot.log_level);
  LoadOptions load = load_options(f.robot.files, f.robot.bus);
  load.config_from_plugin = true;
  // Read on a thread of its own, so that the configuration lives in another allocator arena than the loop's: a
  // reload frees it on a worker thread, which takes that arena's lock for milliseconds at a time; on the main
  // arena, loading a controller after a reload of 10,000 waited 8-15 ms for it (now 2-3 ms, as much as the
  // machine's own scheduling gaps).
  RobotModel model = std::async(std::launch::async, [&] {
                       return load_robot_model(f.robot.files.urdf, f.robot.files.config, load);
                     }).get();
  if (!f.quiet_model) {
    for (const auto& n : model.notes) spdlog::info("{}", n);
    for (const auto& w : model.warnings) spdlog::warn("{}", w);
  }
  if (model.config_path.empty())
    throw ModelError(fmt::format("--config is required: the controllers YAML (a URDF's gz_ros2_control plugin may "
                                 "name it in <parameters>; {}'s does not)",
                                 f.robot.files.urdf));
  const BusFlags& b = f.robot.bus;
  Bus bus(b.lcm_url, model.ns, b.hardware_lcm_url, hardware_reader_named(b.hardware_reader));
  bus.mirror_hardware(b.hardware_mirror_hz);
  // Between two cycles, a request's work (Services), the destruction of unloaded controllers (poll) and the reading
  // of the shared bus (a 4 MiB goal's fragments) take at most this long each before the next hardware state is
  // looked for.
  constexpr int64_t kSliceUs = 250;
  constexpr int64_t kLongestWaitUs = 20000;  // housekeeping (silence, statistics) runs at least this often
  bus.set_pass_budget_us(kSliceUs);
  ManagerOptions options;
  options.silence_us = static_cast<int64_t>(f.silence_s * 1e6);
  options.slice_us = kSliceUs;
  options.intake_thread = true;
  options.command_line = command_line();
  const size_t configured = model.controllers.size();
  const size_t actuated = model.transmissions.size();
  Registry registry = builtin_registry();
  for (const auto& line : load_plugins(registry, plugin_libraries(model))) spdlog::info("{}", line);
  ControllerManager manager(std::move(model), bus, registry, options);
  Services services(manager, bus, kSliceUs);
  for (const auto& c : manager.check_configured()) {
    if (c.outcome != ControllerCheck::Loads) spdlog::warn("configured controller will not load: {}", c.message);
    for (const auto& n : c.notes) spdlog::warn("{}", n);
  }

  install_stop_signals();
  if (const Reply r = manager.publish_config(); !r.ok) spdlog::warn("{}", r.message);  // for a recorder already on

  spdlog::info("ready ({} controllers configured, {} actuated joints, lcm {}{}{}{}{})", configured, actuated, bus.url(),
               hardware_note(bus), bus.ns().empty() ? "" : ", namespace ", bus.ns(),
               scheduling.empty() ? "" : ", " + scheduling);
  int errors = 0;
  while (!stop_requested()) {
    // What is queued, the hardware loop first and at most 1,000 messages each, then the housekeeping: silence
    // is measured after the backlog, so other traffic cannot mask a dead hardware.
    // (Without --spin-us there is no window to wake for: no clock read.)
    int64_t wait_us = f.spin_us > 0 ? manager.state_arrivals().sleep_us(monotonic_us(), f.spin_us, kLongestWaitUs)
                                    : kLongestWaitUs;
    if (services.has_work() || manager.has_work()) wait_us = 0;
    else if (manager.reading_config() || manager.taking_in()) wait_us = std::min<int64_t>(wait_us, 1000);
    if (wait_us == 0) sched_yield();  // spinning: the simulator, woken to its deadline on this CPU, runs first
    if (!bus.handle_us(wait_us, 1000) && !stop_requested()) {
      if (++errors > 100) throw std::runtime_error("LCM keeps failing to receive; giving up");
      continue;
    }
    errors = 0;
    const int64_t now = monotonic_us();
    manager.poll(now);
    services.serve(now + kSliceUs);
  }
  const std::string summary = manager.shutdown();
  services.serve(std::numeric_limits<int64_t>::max());  // what is still queued is refused: shutting down
  spdlog::info("shutting down: {}", summary);
  return kExitOk;
}

}  // namespace lcm_control::cm
