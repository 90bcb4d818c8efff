#include "tools/lib/launch/launcher.hpp"

#include <fmt/ranges.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <memory>
#include <optional>

#include "bus/messages.hpp"
#include "controller_manager/plugins.hpp"
#include "controller_manager/ros_catalog.hpp"
#include "controller_interface/registry.hpp"
#include "description/urdf_reader.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "rt/scheduling.hpp"
#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/launch/launch_file.hpp"
#include "tools/lib/launch/supervisor.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"

namespace lcm_control::tools {
namespace {

// Tells when the servers answer on the bus: a hardware/state from sim_server,
// and an answer to LIST (asked every 0.5 s) from the controller manager.
class ReadinessProbe {
 public:
  explicit ReadinessProbe(Bus& bus) : bus_(bus) {
    state_sub_ = bus_.subscribe(bus_.channel(channels::kHardwareState), &ReadinessProbe::on_state, this,
                                Bus::On::Hardware);
    bus_.subscribe(bus_.channel(channels::kCmResponse), &ReadinessProbe::on_cm, this);
  }
  std::vector<int> fds() { return bus_.fds(); }
  void handle() {
    bus_.handle_shared(100);
    if (bus_.hardware_apart()) bus_.handle_hardware(100);
    if (state_seen_ && state_sub_) {  // one is enough: stop queueing them
      bus_.unsubscribe(state_sub_);
      state_sub_ = 0;
    }
  }
  void ask_manager() {
    const int64_t now = monotonic_us();
    if (cm_answered_ || now - last_list_us_ < 500000) return;
    last_list_us_ = now;
    cm_request_t r = cm_request(cm_request_t::LIST);
    r.utime = wall_us();
    r.request_id = list_id_ = new_request_id();
    r.client = "launch";
    bus_.publish(channels::kCmRequest, r);
  }
  bool hardware_seen() {
    // A state in shared memory makes no descriptor readable (and the bus's socket admits only the channels read
    // here): look at each pump until one is seen.
    if (!state_seen_ && bus_.hardware_shm()) handle();
    return state_seen_;
  }
  bool manager_answered() const { return cm_answered_; }
  const std::string& manager_message() const { return cm_message_; }  // its answer to LIST

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&) { state_seen_ = true; }
  void on_cm(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    cm_response_t m;
    if (decode_guarded(m, rbuf->data, rbuf->data_size) && m.request_id == list_id_) {
      cm_answered_ = true;
      cm_message_ = m.message;
    }
  }
  Bus& bus_;
  int state_sub_ = 0;
  bool state_seen_ = false, cm_answered_ = false;
  int64_t list_id_ = 0, last_list_us_ = 0;
  std::string cm_message_;
};

// The plan's URDF as the servers will read it (only the URDF), or nothing when it does not load: they report why.
std::optional<RobotModel> urdf_of(const LaunchPlan& plan, const std::vector<std::string>& path) {
  LoadOptions o;
  o.package_path = path;
  o.xacro_args = plan.xacro_args;
  o.simulate_hardware = plan.simulate_hardware;
  RobotModel urdf;
  try {
    load_urdf_into(urdf, plan.urdf, o);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  return urdf;
}

// --namespace, else the file's, else the URDF's robotNamespace: what sim_server and controller_manager will use, so
// that launch waits for them where they are.
std::string robot_namespace_of(const LaunchPlan& plan, const std::string& flag, const std::vector<std::string>& path) {
  const std::string given = flag.empty() ? plan.ns : flag;
  if (!given.empty()) return normalize_namespace(given);
  const std::optional<RobotModel> urdf = urdf_of(plan, path);
  return urdf ? robot_namespace("", urdf->gazebo_plugin_namespace) : "";
}

bool spawns(const LaunchPlan& plan) { return !plan.controllers.empty() || !plan.inactive.empty(); }

// What launch takes from the robot's files: for a robot from --urdf/--config (`every_controller`), every controller
// the YAML configures unless --controllers/--inactive name some; for a ROS 2 robot, the config from the
// gz_ros2_control plugin's <parameters> when the file gives none, and a note when nothing says which controllers to
// start (ROS 2 says it in the launch file's spawner calls, not in the YAML).
void model_defaults(LaunchPlan& plan, const std::vector<std::string>& path, const std::string& ns,
                    bool every_controller) {
  LoadOptions o;
  o.package_path = path;
  o.ns = ns;
  o.xacro_args = plan.xacro_args;
  o.args = plan.args;
  o.simulate_hardware = plan.simulate_hardware;
  o.config_from_plugin = true;
  RobotModel model;
  try {
    model = load_robot_model(plan.urdf, plan.configs, o);
  } catch (const ModelError&) {
    throw;  // named here once, before any server starts and names it again
  } catch (const std::exception&) {
    return;  // the servers read the same files and say what is wrong
  }
  if (plan.configs.empty() && !model.config_paths.empty()) {  // load_robot_model took the gz plugin's <parameters>
    plan.configs = model.config_paths;
    launch_say(fmt::format("note: config {} from the URDF's {} plugin <parameters>", model.config_path,
                           model.ros2_control_plugin.filename));
  }
  if (plan.configs.empty())
    throw ModelError(fmt::format("{}: 'config' is missing: the controllers YAML (a URDF's gz_ros2_control plugin may "
                                 "name it in <parameters>; {}'s does not)",
                                 plan.file, plan.urdf));
  std::vector<std::string> names;
  for (const auto& c : model.controllers) names.push_back(c.name);
  if (every_controller && !spawns(plan)) {
    // Every controller the YAML configures but those of types not available here (another package's, as a ROS 2
    // YAML declares its vendor's controllers for launch files that never spawn them): one note each.
    cm::Registry registry = cm::builtin_registry();
    for (const auto& line : cm::load_plugins(registry, cm::plugin_libraries(model))) launch_say("note: " + line);
    for (const auto& c : model.controllers) {
      if (registry.has(c.type) || registry.misspelling(c.type)) {
        plan.controllers.push_back(c.name);
        continue;
      }
      launch_say(fmt::format("note: not starting '{}': {}", c.name, unknown_type_message(registry, c.type)));
    }
    return;
  }
  if (!model.ros2_parameter_file || spawns(plan)) return;
  launch_say(fmt::format("note: {} configures {}; a ROS 2 launch starts controllers in its spawner calls: name them "
                         "with --controllers a,b (and --inactive c), or `controllers:` / `inactive:` in a launch "
                         "file. Starting none.",
                         model.config_path, names.empty() ? "no controllers" : fmt::format("{}", fmt::join(names, ", "))));
}

}  // namespace

std::vector<std::string> with_ns(std::vector<std::string> argv, const std::string& ns) {
  if (!ns.empty()) {
    argv.push_back("--namespace");
    argv.push_back(ns);
  }
  return argv;
}

CommandLines command_lines(const LaunchPlan& plan, const LaunchOptions& o, const std::string& hw_url, bool hw_apart) {
  CommandLines lines;
  auto& [sim, cm, spawner, rsp, dash] = lines;
  std::vector<std::string> file_args;
  for (const auto& [name, value] : plan.args) file_args.insert(file_args.end(), {"--arg", name + "=" + value});
  std::vector<std::string> urdf_args;  // a .xacro urdf's arguments, for every process that reads the robot file
  for (const auto& [name, value] : plan.xacro_args)
    urdf_args.insert(urdf_args.end(), {"--xacro-arg", name + ":=" + value});
  file_args.insert(file_args.end(), urdf_args.begin(), urdf_args.end());
  for (const auto& name : plan.simulate_hardware) file_args.insert(file_args.end(), {"--simulate-hardware", name});
  std::vector<std::string> robot_files{"--urdf", plan.urdf};
  for (const auto& c : plan.configs) robot_files.insert(robot_files.end(), {"--config", c});
  file_args.insert(file_args.begin(), robot_files.begin(), robot_files.end());
  sim = {"sim_server"};
  sim.insert(sim.end(), file_args.begin(), file_args.end());
  for (const auto& [joint, q] : plan.initial_positions)
    sim.insert(sim.end(), {"--initial-position", fmt::format("{}={}", joint, q)});
  if (plan.mode == "lockstep") sim.insert(sim.end(), {"--mode", "lockstep"});
  if (plan.paused) sim.push_back("--paused");
  if (plan.base == "fixed") sim.push_back("--fixed-base");
  if (plan.base == "floating") sim.push_back("--floating-base");
  if (plan.base_pose) {
    sim.push_back("--base-pose");
    for (double v : *plan.base_pose) sim.push_back(fmt::format("{:g}", v));
  }
  if (plan.physics_rate > 0) sim.insert(sim.end(), {"--physics-rate", fmt::format("{:g}", plan.physics_rate)});
  if (plan.control_rate > 0) sim.insert(sim.end(), {"--control-rate", fmt::format("{:g}", plan.control_rate)});
  sim.insert(sim.end(), plan.sim_args.begin(), plan.sim_args.end());
  if (o.duration > 0) sim.insert(sim.end(), {"--duration", fmt::format("{:g}", o.duration)});
  cm = {"controller_manager"};
  cm.insert(cm.end(), file_args.begin(), file_args.end());
  if (plan.sim) cm.push_back("--quiet-model");  // sim_server reads the same files and prints the same warnings
  cm.insert(cm.end(), plan.cm_args.begin(), plan.cm_args.end());
  // In lockstep the two loop processes take turns; on one CPU each hand-over is a cheaper wake-up (bench/README.md).
  int pin = -1;
  if (plan.cpu == "auto" && plan.mode == "lockstep") pin = least_busy_cpu();
  if (plan.cpu != "auto" && plan.cpu != "none") pin = std::stoi(plan.cpu);
  // The real-time profile, where the file's own flags for a process do not set it already.
  const int spin = plan.mode == "realtime" ? effective_spin_us(plan) : 0;
  for (auto [argv, extra] : {std::pair{&sim, &plan.sim_args}, std::pair{&cm, &plan.cm_args}}) {
    if (pin >= 0) argv->insert(argv->end(), {"--cpu", std::to_string(pin)});
    if (hw_apart) argv->insert(argv->end(), {"--hardware-url", hw_url});
    if (hw_apart && plan.hardware_mirror_hz > 0 && is_shm_url(hw_url))
      argv->insert(argv->end(), {"--hardware-mirror", fmt::format("{:g}", plan.hardware_mirror_hz)});
    auto unset = [&](const std::string& flag) {
      return std::none_of(extra->begin(), extra->end(),
                          [&](const std::string& e) { return e == flag || e.rfind(flag + "=", 0) == 0; });
    };
    if (plan.rt_priority > 0 && unset("--rt-priority"))
      argv->insert(argv->end(), {"--rt-priority", std::to_string(plan.rt_priority)});
    if (spin > 0 && unset("--spin-us")) argv->insert(argv->end(), {"--spin-us", std::to_string(spin)});
  }
  spawner = {"spawner"};
  spawner.insert(spawner.end(), plan.controllers.begin(), plan.controllers.end());
  for (const auto& n : plan.inactive) spawner.insert(spawner.end(), {"--load-inactive", n});
  spawner.insert(spawner.end(), {"--shutdown-timeout", fmt::format("{:g}", o.stop_timeout * 0.3)});
  if (plan.sim && plan.mode == "lockstep") spawner.push_back("--hardware-later");  // the sim starts after it
  spawner.insert(spawner.end(), plan.spawner_args.begin(), plan.spawner_args.end());
  rsp = {"state-publisher"};
  rsp.insert(rsp.end(), file_args.begin(), file_args.end());
  dash = {"dashboard", "--urdf", plan.urdf, "--port", std::to_string(o.dashboard_port)};
  dash.insert(dash.end(), urdf_args.begin(), urdf_args.end());
  return lines;
}

namespace {

void print_dry_run(const LaunchPlan& plan, const LaunchOptions& o, const CommandLines& lines, const std::string& ns) {
  const auto& [sim, cm, spawner, rsp, dash] = lines;
  if (plan.sim) fmt::print("{}: {}\n", plan.sim_name, fmt::join(with_ns(sim, ns), " "));
  if (plan.controller_manager) fmt::print("{}: {}\n", plan.cm_name, fmt::join(with_ns(cm, ns), " "));
  if (plan.state_publisher) fmt::print("{}: {}\n", plan.state_publisher_name, fmt::join(with_ns(rsp, ns), " "));
  if (o.dashboard) fmt::print("dashboard: {}\n", fmt::join(with_ns(dash, ns), " "));
  for (const auto& p : plan.processes)
    fmt::print("{}: {}{}\n", p.name, fmt::join(p.argv, " "), p.required ? " (required)" : "");
  if (spawns(plan)) fmt::print("{}: {}\n", plan.spawner_name, fmt::join(with_ns(spawner, ns), " "));
  for (const auto& c : plan.commands)
    fmt::print("command source: {} [{}] rate {:g} count {} duration {:g}\n", c.target, fmt::join(c.expr, ", "), c.rate,
               c.count, c.duration);
}

// Starts the processes in order, waits until each answers, then until one fails, Ctrl-C or the sim's --duration
// ends the run, and stops them in order: controllers, helpers, then the controller manager and the sim.
int supervise(const LaunchPlan& plan, const LaunchOptions& o, const CommandLines& lines, const std::string& ns,
              const std::string& hw_url) {
  const auto& [sim, cm, spawner, rsp, dash] = lines;
  install_stop_signals();
  auto bus = std::make_unique<Bus>(o.bus.lcm_url, ns, hw_url, HardwareReader::Direct);
  std::vector<std::pair<std::string, std::string>> env{{"LCM_DEFAULT_URL", bus->url()}};
  if (!o.package_path.empty())
    env.emplace_back("LCM_CONTROL_PACKAGE_PATH", fmt::format("{}", fmt::join(o.package_path, ":")));
  Supervisor sup(env);
  auto probe = std::make_unique<ReadinessProbe>(*bus);
  sup.watch(probe->fds(), [&] { probe->handle(); });
  // A robot already up on this namespace would fight the one started here: its simulator takes the commands of
  // one manager and drops the other's, and each manager follows one of two simulators.
  sup.wait_until(
      [&] {
        if (plan.controller_manager) probe->ask_manager();
        return probe->manager_answered() || (plan.sim && probe->hardware_seen());
      },
      0.6);
  const std::string where = ns.empty() ? "the default namespace" : "namespace '" + ns + "'";
  if (plan.controller_manager && probe->manager_answered())
    throw std::runtime_error(fmt::format(
        "a controller manager already answers on '{}' in {} ({}): a second one would fight it for the robot. Stop "
        "the robot that runs there (Ctrl-C its launch), or launch this one with --namespace NAME or another "
        "--lcm-url",
        bus->channel(channels::kCmResponse), where, probe->manager_message()));
  if (plan.sim && probe->hardware_seen())
    throw std::runtime_error(fmt::format(
        "hardware already publishes '{}' in {}: a second simulator there would make two sessions the controller "
        "manager cannot both follow. Stop it, or launch this robot with --namespace NAME or another --lcm-url",
        bus->channel(channels::kHardwareState), where));
  Child *sim_c = nullptr, *cm_c = nullptr, *spawner_c = nullptr;
  std::vector<Child*> others;
  std::string failure;

  const int64_t up_deadline = monotonic_us() + int64_t(o.ready_timeout * 1e6);
  auto left = [&] { return std::max(0.0, double(up_deadline - monotonic_us()) / 1e6); };
  auto broken = [&] { return stop_requested() || !sup.reason_to_stop().empty(); };
  const bool sim_last = plan.sim && plan.mode == "lockstep";
  if (plan.sim && !sim_last) sim_c = &sup.start(plan.sim_name, with_ns(sim, ns), true);
  if (plan.controller_manager) cm_c = &sup.start(plan.cm_name, with_ns(cm, ns), true);
  const bool servers_up = sup.wait_until(
      [&] {
        if (cm_c && cm_c->ready) probe->ask_manager();
        return broken() || ((!sim_c || (sim_c->ready && probe->hardware_seen())) &&
                            (!cm_c || (cm_c->ready && probe->manager_answered())));
      },
      left());
  if (!servers_up) {
    std::vector<std::string> waiting;
    if (sim_c && !sim_c->ready) waiting.push_back(plan.sim_name + " (no 'ready' line)");
    if (sim_c && sim_c->ready && !probe->hardware_seen())
      waiting.push_back(fmt::format("{} (nothing on '{}')", plan.sim_name, bus->channel(channels::kHardwareState)));
    if (cm_c && !cm_c->ready) waiting.push_back(plan.cm_name + " (no 'ready' line)");
    if (cm_c && cm_c->ready && !probe->manager_answered())
      waiting.push_back(fmt::format("{} (no answer on '{}')", plan.cm_name, bus->channel(channels::kCmResponse)));
    failure = fmt::format("not up within {}: {}", seconds_text(o.ready_timeout), fmt::join(waiting, ", "));
  }
  // From here launch needs no bus; a udpm socket receives every message on
  // it, which costs CPU the simulation could use.
  auto drop_bus = [&] {
    sup.watch({}, {});
    probe.reset();
    bus.reset();
  };
  if (failure.empty() && !broken()) {
    if (!sim_last && plan.commands.empty()) drop_bus();
    if (plan.state_publisher) others.push_back(&sup.start(plan.state_publisher_name, with_ns(rsp, ns), true));
    for (const auto& p : plan.processes) others.push_back(&sup.start(p.name, p.argv, p.required));
    if (o.dashboard) others.push_back(&sup.start("dashboard", with_ns(dash, ns), false));
    if (spawns(plan)) {
      spawner_c = &sup.start(plan.spawner_name, with_ns(spawner, ns), true);
      if (!sup.wait_until([&] { return broken() || spawner_c->ready; }, std::max(left(), 12.0)))
        failure = fmt::format("{} did not report its controllers running within {}", plan.spawner_name,
                              seconds_text(std::max(left(), 12.0)));
    }
  }
  if (failure.empty() && !broken() && !plan.commands.empty()) {
    CmClient client(*bus, "launch");
    for (const auto& c : plan.commands) {
      command_source_t req{};
      req.controller = c.target;
      req.expressions = c.expr;
      req.rate_hz = c.rate;
      req.count = c.count;
      req.duration_s = c.duration;
      try {
        const cm_response_t r = client.command_source(req, std::max(left(), 5.0));
        if (!r.ok) {
          failure = r.message;
          break;
        }
        launch_say(r.message);
      } catch (const CmTimeout& e) {
        failure = e.what();
        break;
      }
    }
  }
  if (failure.empty() && !broken() && sim_last) {
    sim_c = &sup.start(plan.sim_name, with_ns(sim, ns), true);
    if (!sup.wait_until([&] { return broken() || (sim_c->ready && probe->hardware_seen()); }, std::max(left(), 5.0)))
      failure = fmt::format("{} not up within {}: {}", plan.sim_name, seconds_text(std::max(left(), 5.0)),
                            sim_c->ready ? fmt::format("nothing on '{}'", bus->channel(channels::kHardwareState))
                                         : std::string("no 'ready' line"));
  }
  if (bus) drop_bus();
  if (failure.empty() && !broken()) {
    // The spawner's ready line ends "; failed: A, B (Ctrl-C ..." when some controllers could not be spawned: the
    // robot stays up with the others, as with ROS's spawner, and launch's exit status says so at the end.
    std::vector<std::string> failed_names;
    if (spawner_c) {
      const std::string& line = spawner_c->ready_line;
      const auto at = line.find("; failed: ");
      if (at != std::string::npos) {
        const std::string list = line.substr(at + 10, line.find(" (Ctrl-C", at) - at - 10);
        for (size_t b = 0; b <= list.size();) {
          const size_t e = std::min(list.find(", ", b), list.size());
          if (e > b) failed_names.push_back(list.substr(b, e - b));
          b = e + 2;
        }
      }
    }
    auto spawned = [&](const std::vector<std::string>& names) {
      std::vector<std::string> out;
      for (const auto& n : names)
        if (std::find(failed_names.begin(), failed_names.end(), n) == failed_names.end()) out.push_back(n);
      return out;
    };
    const std::vector<std::string> running = spawned(plan.controllers), inactive = spawned(plan.inactive);
    launch_say(fmt::format("up: {}{}{}{} (Ctrl-C to stop)", running.empty() ? "no controllers" : "controllers ",
                           fmt::join(running, ", "),
                           inactive.empty() ? "" : fmt::format("; inactive {}", fmt::join(inactive, ", ")),
                           failed_names.empty()
                               ? ""
                               : fmt::format("; FAILED to spawn {} (the reason is in [{}]'s lines above; launch "
                                             "will exit 1)",
                                             fmt::join(failed_names, ", "), plan.spawner_name)));
    sup.wait_until(broken, 1e12);
  }
  std::string why = failure;
  if (why.empty()) why = sup.reason_to_stop();
  if (why.empty() && stop_requested()) why = fmt::format("got {}", strsignal(stop_signal()));
  clear_stop();
  launch_say(fmt::format("stopping ({})", why));

  // Controllers first, then the helpers, then the controller manager and the sim.
  const int64_t t0 = monotonic_us(), budget = int64_t(o.stop_timeout * 1e6);
  if (spawner_c) sup.stop({spawner_c}, t0 + budget / 2);
  sup.stop(others, t0 + budget * 7 / 10);
  std::vector<Child*> servers;
  if (cm_c) servers.push_back(cm_c);
  if (sim_c) servers.push_back(sim_c);
  sup.stop(servers, t0 + budget);

  std::vector<std::string> failed;
  for (const auto& c : sup.children())
    if (!c->clean()) failed.push_back(Supervisor::exit_text(*c));
  launch_say(
      fmt::format("all {} processes stopped in {:.2f} s", sup.children().size(), double(monotonic_us() - t0) / 1e6));
  // A child that refused a bad file (exit 3) by itself makes launch exit 3 too, as the convention says.
  const bool bad_file = std::any_of(sup.children().begin(), sup.children().end(), [](const auto& c) {
    return c->exited && !c->signalled && c->code == int(kExitBadInput);
  });
  const std::string message = !failure.empty() ? failure : fmt::format("{}", fmt::join(failed, "; "));
  if (bad_file && !message.empty()) throw ModelError(message);
  if (!message.empty()) throw std::runtime_error(message);
  return int(kExitOk);
}

}  // namespace

void launch_say(const std::string& line) {
  fmt::print("[launch] {}\n", line);
  std::fflush(stdout);
}

LaunchPlan plan_from_flags(const LaunchOptions& o) {
  if (!o.file.empty() && !o.urdf.empty())
    throw CLI::ValidationError("--urdf", "give a launch FILE or --urdf (with --config), not both");
  if (o.urdf.empty())
    throw CLI::ValidationError("FILE", "give a launch FILE, or the robot with --urdf R.urdf --config C.yaml");
  LaunchPlan plan;
  plan.file = o.urdf;
  plan.urdf = std::filesystem::absolute(o.urdf).string();
  for (const auto& c : o.configs) plan.configs.push_back(std::filesystem::absolute(c).string());
  return plan;  // the controllers: model_defaults
}

LaunchPlan resolve_launch(const LaunchOptions& o) {
  const bool from_flags = o.file.empty() || !o.urdf.empty();
  if (!from_flags && !o.configs.empty())
    throw CLI::ValidationError("--config", "goes with --urdf; a launch FILE names its own config");
  std::vector<std::pair<std::string, std::string>> args;
  for (const auto& a : o.args) args.push_back(parse_arg(a));
  LaunchPlan plan = from_flags ? plan_from_flags(o) : read_launch_file(o.file, o.package_path, args, o.embedding_keys);
  if (o.dashboard && (o.robots > 0 || !plan.robots.empty()))
    throw CLI::ValidationError("--dashboard",
                               "one dashboard shows one robot: with several, start one per robot "
                               "(dashboard --namespace r0 --port 8080 --urdf FILE, r1 on 8081, ...)");
  if (!o.mode.empty()) plan.mode = o.mode;
  for (const auto& a : o.xacro_args) plan.xacro_args.push_back(parse_arg(a));  // after the file's: the flag wins
  for (const auto& a : o.args) {
    const auto given = parse_arg(a);
    plan.args.erase(std::remove_if(plan.args.begin(), plan.args.end(),
                                   [&](const auto& f) { return f.first == given.first; }),
                    plan.args.end());
    plan.args.push_back(given);
  }
  if (o.paused) plan.paused = true;
  if (!o.base.empty()) plan.base = o.base;
  if (o.physics) plan.sim_args.push_back("--physics");
  for (const auto& name : o.simulate_hardware)
    if (std::find(plan.simulate_hardware.begin(), plan.simulate_hardware.end(), name) == plan.simulate_hardware.end())
      plan.simulate_hardware.push_back(name);
  if (o.bus.hardware_mirror_hz > 0) plan.hardware_mirror_hz = o.bus.hardware_mirror_hz;
  if (!o.cpu.empty()) plan.cpu = o.cpu;
  if (o.rt_priority >= 0) plan.rt_priority = o.rt_priority;
  if (o.spin_us >= 0) plan.spin_us = o.spin_us;
  if (!o.controllers.empty()) plan.controllers = o.controllers;
  if (!o.inactive.empty()) plan.inactive = o.inactive;
  for (const auto& n : plan.notes) launch_say("note: " + n);
  model_defaults(plan, o.package_path, o.bus.ns.empty() ? plan.ns : o.bus.ns, from_flags);
  if (o.robots > 0) plan.robots = robot_names(o.robots);
  return plan;
}

int run_launch(const LaunchOptions& o) {
  const LaunchPlan plan = resolve_launch(o);
  if (!plan.robots.empty()) return run_robots(o, plan);
  const std::string ns = robot_namespace_of(plan, o.bus.ns, o.package_path);
  const std::string hw_flag = !o.bus.hardware_lcm_url.empty() ? o.bus.hardware_lcm_url : plan.hardware_lcm_url;
  const std::string hw_url = hardware_url_for(hw_flag, effective_url(o.bus.lcm_url), ns);
  const bool hw_apart = hw_url != effective_url(o.bus.lcm_url);
  if (plan.hardware_mirror_hz > 0 && !is_shm_url(hw_url))
    throw BusError(fmt::format("hardware mirror {:g}: the hardware loop is on LCM ({}), where every tool hears it "
                               "already; the mirror is for a shm hardware URL (--hardware-url shm or `hardware_url: "
                               "shm`)",
                               plan.hardware_mirror_hz, hw_url));
  const CommandLines lines = command_lines(plan, o, hw_url, hw_apart);
  if (o.dry_run) {
    print_dry_run(plan, o, lines, ns);
    return int(kExitOk);
  }
  return supervise(plan, o, lines, ns, hw_url);
}

}  // namespace lcm_control::tools
