// launch: roslaunch for lcm_control. Starts sim_server and controller_manager
// from a YAML or ROS XML launch file, waits until both answer, spawns the
// controllers, registers the file's command sources, prefixes every child's
// output with its name, and stops everything in order (controllers, then
// processes) on Ctrl-C, a death, or when sim_server ends its --duration. In
// lockstep, sim_server starts last, so controllers and command sources start at
// step 0 in every run.
#include <fmt/ranges.h>

#include <algorithm>
#include <cstring>
#include <memory>

#include "cli/cli.hpp"
#include "bus/messages.hpp"
#include "rt/scheduling.hpp"
#include "description/urdf_reader.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "tools/lib/cm_client.hpp"
#include "tools/lib/launch_file.hpp"
#include "tools/lib/supervisor.hpp"
#include "tools/lib/support.hpp"

namespace lcm_control::tools {
namespace {

void say(const std::string& line) {
  fmt::print("[launch] {}\n", line);
  std::fflush(stdout);
}

// Tells when the servers answer on the bus: a hardware/state from sim_server,
// and an answer to LIST (asked every 0.5 s) from the controller manager.
class ReadinessProbe {
 public:
  explicit ReadinessProbe(Bus& bus) : bus_(bus) {
    state_sub_ = bus_.hardware().subscribe(bus_.channel(channels::kHardwareState), &ReadinessProbe::on_state, this);
    bus_.lcm().subscribe(bus_.channel(channels::kCmResponse), &ReadinessProbe::on_cm, this);
  }
  std::vector<int> fds() { return bus_.fds(); }
  void handle() {
    for (lcm::LCM* lc : {&bus_.lcm(), &bus_.hardware()})
      for (int n = 0; n < 100 && lc->handleTimeout(0) > 0; ++n) {
      }
    if (state_seen_ && state_sub_) {  // one is enough: stop queueing them
      bus_.hardware().unsubscribe(state_sub_);
      state_sub_ = nullptr;
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
  bool hardware_seen() const { return state_seen_; }
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
  lcm::Subscription* state_sub_ = nullptr;
  bool state_seen_ = false, cm_answered_ = false;
  int64_t list_id_ = 0, last_list_us_ = 0;
  std::string cm_message_;
};

// --namespace, else the file's, else the URDF's robotNamespace: what sim_server and controller_manager will use, so
// that launch waits for them where they are. A URDF that does not load is left for them to report.
std::string robot_namespace_of(const LaunchPlan& plan, const std::string& flag, const std::vector<std::string>& path) {
  const std::string given = flag.empty() ? plan.ns : flag;
  if (!given.empty()) return normalize_namespace(given);
  LoadOptions o;
  o.package_path = path;
  o.xacro_args = plan.xacro_args;
  RobotModel urdf;
  try {
    load_urdf_into(urdf, plan.urdf, o);
  } catch (const std::exception&) {
    return "";
  }
  return robot_namespace("", urdf.gazebo_plugin_namespace);
}

std::vector<std::string> with_ns(std::vector<std::string> argv, const std::string& ns) {
  if (!ns.empty()) {
    argv.push_back("--namespace");
    argv.push_back(ns);
  }
  return argv;
}

struct RobotsOptions {
  std::string file;
  std::vector<std::string> robots;  // namespaces
  std::vector<std::string> args;    // for every robot's launch
  double ready_timeout = 20, stop_timeout = 5;
  bool dry_run = false;
};

// launch --robots / `robots:`: one launch of the file per robot, in its namespace, supervised as one: up when all
// are, stopped together when one fails or on Ctrl-C.
int run_robots(const RobotsOptions& o, const std::string& url, const std::vector<std::string>& package_path) {
  std::vector<std::vector<std::string>> argvs;
  for (const auto& r : o.robots) {
    std::vector<std::string> argv{"launch", o.file, "--namespace", r};
    argv.insert(argv.end(), o.args.begin(), o.args.end());
    argvs.push_back(argv);
  }
  if (o.dry_run) {
    for (size_t i = 0; i < o.robots.size(); ++i) fmt::print("{}: {}\n", o.robots[i], fmt::join(argvs[i], " "));
    return int(kExitOk);
  }
  install_stop_signals();
  std::vector<std::pair<std::string, std::string>> env{{"LCM_DEFAULT_URL", url}};
  if (!package_path.empty()) env.emplace_back("LCM_CONTROL_PACKAGE_PATH", fmt::format("{}", fmt::join(package_path, ":")));
  Supervisor sup(env);
  std::vector<Child*> children;
  for (size_t i = 0; i < o.robots.size(); ++i)
    children.push_back(&sup.start(o.robots[i], argvs[i], true, "[launch] up: "));
  // A robot whose launch ends by itself with 0 (its --duration) is done; one that fails stops the others.
  auto failed = [&] {
    for (const Child* c : children)
      if (c->exited && !c->signalled && c->code != 0) return Supervisor::exit_text(*c);
    return std::string();
  };
  auto broken = [&] { return stop_requested() || !failed().empty(); };
  auto all = [&](bool Child::*flag) {
    return std::all_of(children.begin(), children.end(), [&](const Child* c) { return c->*flag; });
  };
  const bool up = sup.wait_until([&] { return broken() || all(&Child::ready) || all(&Child::exited); },
                                 o.ready_timeout + 5);
  std::string failure;
  if (!up) {
    std::vector<std::string> waiting;
    for (const Child* c : children)
      if (!c->ready) waiting.push_back(c->name);
    failure = fmt::format("not up within {}: {}", seconds_text(o.ready_timeout + 5), fmt::join(waiting, ", "));
  }
  if (failure.empty() && !broken()) {
    say(fmt::format("up: {} robots ({}) (Ctrl-C to stop)", o.robots.size(), fmt::join(o.robots, ", ")));
    sup.wait_until([&] { return broken() || all(&Child::exited); }, 1e12);
  }
  std::string why = failure;
  if (why.empty()) why = failed();
  if (why.empty() && all(&Child::exited)) why = "every robot's launch ended";
  if (why.empty() && stop_requested()) why = fmt::format("got {}", strsignal(stop_signal()));
  clear_stop();
  say(fmt::format("stopping ({})", why));
  const int64_t t0 = monotonic_us();
  sup.stop(children, t0 + int64_t((o.stop_timeout + 2) * 1e6));
  std::vector<std::string> unclean;
  for (const auto& c : sup.children())
    if (!c->clean()) unclean.push_back(Supervisor::exit_text(*c));
  say(fmt::format("all {} robots stopped in {:.2f} s", children.size(), double(monotonic_us() - t0) / 1e6));
  if (!failure.empty()) throw std::runtime_error(failure);
  if (!unclean.empty()) throw std::runtime_error(fmt::format("{}", fmt::join(unclean, "; ")));
  return int(kExitOk);
}

}  // namespace
}  // namespace lcm_control::tools

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Start sim_server and controller_manager from one launch file, wait until both answer, spawn the controllers, "
      "and stop everything in order on Ctrl-C or when a process dies (exit 1 if one failed). Reads our YAML launch "
      "files and ROS launch XML (gazebo_ros_control.launch: <param textfile>, <rosparam load>, $(find PKG), the "
      "spawner's args; gazebo -> sim_server, robot_state_publisher -> state-publisher). Children get "
      "LCM_DEFAULT_URL; every output line is prefixed with the child's name.\n"
      "Examples:\n"
      "  launch config/turret_bot.launch.yaml\n"
      "  launch ~/catkin_ws/src/turret_bot/launch/gazebo_ros_control.launch --package-path ~/catkin_ws/src\n"
      "  launch config/turret_bot.launch.yaml --mode lockstep --dry-run\n"
      "  launch config/turret_bot_demo.launch.yaml --duration 20       # lockstep demo, exits when done\n"
      "In lockstep mode the controller manager starts first, the controllers are spawned and the file's commands "
      "registered as command sources, and only then sim_server starts: every run is the same from step 0.",
      "launch"};
  std::string file, mode, cpu;
  std::vector<std::string> package_path;
  double ready_timeout = 20, stop_timeout = 5, duration = 0;
  bool dry_run = false;
  BusFlags bus_flags;
  app.add_option("FILE", file, "launch file: YAML (see config/turret_bot.launch.yaml) or ROS launch XML")->required();
  app.add_option("--mode", mode, "override the file's mode: realtime or lockstep")
      ->check(CLI::IsMember({"realtime", "lockstep"}));
  bool paused = false;
  app.add_flag("--paused", paused,
               "start sim_server paused (Gazebo's paused:=true): controllers are spawned, nothing moves until "
               "`cmctl resume`");
  app.add_option("--cpu", cpu,
                 "override the file's cpu: auto (lockstep: sim_server and controller_manager share the least busy "
                 "CPU), none, or a CPU number")
      ->check([](const std::string& v) { return check_cpu(v); });
  int rt_priority = -1, spin_us = -1;
  app.add_option("--rt-priority", rt_priority,
                 "run sim_server and controller_manager at SCHED_FIFO with this priority (1-99) and memory locked, "
                 "and in real time let each spin the last --spin-us before its deadline; 0: the normal scheduler "
                 "(overrides the file's rt_priority; needs root, CAP_SYS_NICE or `ulimit -r`)")
      ->check(CLI::Range(0, kMaxRtPriority));
  app.add_option("--spin-us", spin_us,
                 fmt::format("microseconds each loop process spins before its real-time deadline instead of "
                             "sleeping (default {} with --rt-priority, else 0; overrides the file's spin_us)",
                             kRealTimeSpinUs))
      ->check(CLI::Range(0, kMaxSpinUs));
  app.add_option("--ready-timeout", ready_timeout, "seconds for the servers and the spawner to come up")
      ->check(CLI::PositiveNumber);
  app.add_option("--stop-timeout", stop_timeout, "seconds for everything to stop before the rest is killed")
      ->check(CLI::PositiveNumber);
  app.add_option("--duration", duration,
                 "sim seconds: passed to sim_server, which stops then; launch then stops the rest and exits 0")
      ->check(CLI::PositiveNumber);
  app.add_flag("--dry-run", dry_run, "print what would be started and exit");
  add_package_path_flag(app, package_path);
  std::vector<std::string> xacro_args;
  add_xacro_arg_flag(app, xacro_args);
  add_bus_flags(app, bus_flags);
  add_hardware_url_flag(app, bus_flags);
  int robots = 0;
  app.add_option("--robots", robots,
                 "start this many copies of the robot, in namespaces r0, r1, ..., each with its hardware loop on its "
                 "own port (--hardware-lcm-url auto unless given; `shared` keeps them on the --lcm-url); overrides "
                 "the file's `robots:`")
      ->check(CLI::Range(1, kMaxRobots));
  bool dashboard = false;
  int dashboard_port = 8080;
  app.add_flag("--dashboard", dashboard,
               "also start the dashboard (the robot in a browser: plots, sliders, gains, controllers) once the "
               "servers are up, and print its URL");
  app.add_option("--dashboard-port", dashboard_port, "the dashboard's port (default 8080; 0: one the system picks)")
      ->check(CLI::Range(0, 65535));
  return run_program(app, argc, argv, [&]() -> int {
    LaunchPlan plan = read_launch_file(file, package_path);
    if (dashboard && (robots > 0 || !plan.robots.empty()))
      throw CLI::ValidationError("--dashboard", "one dashboard shows one robot: with several, start one per robot "
                                                "(dashboard --namespace r0 --port 8080 --urdf FILE, r1 on 8081, ...)");
    if (!mode.empty()) plan.mode = mode;
    for (const auto& a : xacro_args) plan.xacro_args.push_back(parse_arg(a));  // after the file's: the flag wins
    if (paused) plan.paused = true;
    if (!cpu.empty()) plan.cpu = cpu;
    if (rt_priority >= 0) plan.rt_priority = rt_priority;
    if (spin_us >= 0) plan.spin_us = spin_us;
    for (const auto& n : plan.notes) say("note: " + n);

    if (robots > 0) plan.robots = robot_names(robots);
    if (!plan.robots.empty()) {
      RobotsOptions ro{file, plan.robots, {}, ready_timeout, stop_timeout, dry_run};
      auto pass = [&](const char* flag, const std::string& value) {
        if (!value.empty()) ro.args.insert(ro.args.end(), {flag, value});
      };
      pass("--mode", mode);
      if (paused) ro.args.push_back("--paused");
      pass("--cpu", cpu);
      if (rt_priority >= 0) pass("--rt-priority", std::to_string(rt_priority));
      if (spin_us >= 0) pass("--spin-us", std::to_string(spin_us));
      pass("--ready-timeout", fmt::format("{:g}", ready_timeout));
      pass("--stop-timeout", fmt::format("{:g}", stop_timeout));
      if (duration > 0) pass("--duration", fmt::format("{:g}", duration));
      if (!package_path.empty()) pass("--package-path", fmt::format("{}", fmt::join(package_path, ":")));
      for (const auto& a : xacro_args) pass("--xacro-arg", a);
      pass("--lcm-url", bus_flags.lcm_url);
      const std::string hw = !bus_flags.hardware_lcm_url.empty() ? bus_flags.hardware_lcm_url
                             : !plan.hardware_lcm_url.empty()   ? plan.hardware_lcm_url
                                                                : "auto";
      pass("--hardware-lcm-url", hw);
      if (!plan.ns.empty() || !bus_flags.ns.empty())
        say(fmt::format("note: the robots' namespaces ({}) replace namespace '{}'", fmt::join(plan.robots, ", "),
                        bus_flags.ns.empty() ? plan.ns : bus_flags.ns));
      return run_robots(ro, effective_url(bus_flags.lcm_url), package_path);
    }
    const std::string ns = robot_namespace_of(plan, bus_flags.ns, package_path);
    const std::string hw_flag = !bus_flags.hardware_lcm_url.empty() ? bus_flags.hardware_lcm_url : plan.hardware_lcm_url;
    const std::string hw_url = hardware_url_for(hw_flag, effective_url(bus_flags.lcm_url), ns);
    const bool hw_apart = hw_url != effective_url(bus_flags.lcm_url);
    std::vector<std::string> file_args;
    for (const auto& [name, value] : plan.args) file_args.insert(file_args.end(), {"--arg", name + "=" + value});
    std::vector<std::string> urdf_args;  // a .xacro urdf's arguments, for every process that reads the robot file
    for (const auto& [name, value] : plan.xacro_args)
      urdf_args.insert(urdf_args.end(), {"--xacro-arg", name + ":=" + value});
    file_args.insert(file_args.end(), urdf_args.begin(), urdf_args.end());
    std::vector<std::string> sim{"sim_server", "--urdf", plan.urdf, "--config", plan.config};
    sim.insert(sim.end(), file_args.begin(), file_args.end());
    for (const auto& [joint, q] : plan.initial_positions)
      sim.insert(sim.end(), {"--initial-position", fmt::format("{}={}", joint, q)});
    if (plan.mode == "lockstep") sim.insert(sim.end(), {"--mode", "lockstep"});
    if (plan.paused) sim.push_back("--paused");
    if (plan.physics_rate > 0) sim.insert(sim.end(), {"--physics-rate", fmt::format("{:g}", plan.physics_rate)});
    if (plan.control_rate > 0) sim.insert(sim.end(), {"--control-rate", fmt::format("{:g}", plan.control_rate)});
    sim.insert(sim.end(), plan.sim_args.begin(), plan.sim_args.end());
    if (duration > 0) sim.insert(sim.end(), {"--duration", fmt::format("{:g}", duration)});
    std::vector<std::string> cm{"controller_manager", "--urdf", plan.urdf, "--config", plan.config};
    cm.insert(cm.end(), file_args.begin(), file_args.end());
    cm.insert(cm.end(), plan.cm_args.begin(), plan.cm_args.end());
    // In lockstep the two loop processes take turns; on one CPU each hand-over is a cheaper wake-up (bench/README.md).
    int pin = -1;
    if (plan.cpu == "auto" && plan.mode == "lockstep") pin = least_busy_cpu();
    if (plan.cpu != "auto" && plan.cpu != "none") pin = std::stoi(plan.cpu);
    // The real-time profile, where the file's own flags for a process do not set it already.
    const int spin = plan.mode == "realtime" ? effective_spin_us(plan) : 0;
    for (auto [argv, extra] : {std::pair{&sim, &plan.sim_args}, std::pair{&cm, &plan.cm_args}}) {
      if (pin >= 0) argv->insert(argv->end(), {"--cpu", std::to_string(pin)});
      if (hw_apart) argv->insert(argv->end(), {"--hardware-lcm-url", hw_url});
      auto unset = [&](const std::string& flag) {
        return std::none_of(extra->begin(), extra->end(),
                            [&](const std::string& e) { return e == flag || e.rfind(flag + "=", 0) == 0; });
      };
      if (plan.rt_priority > 0 && unset("--rt-priority"))
        argv->insert(argv->end(), {"--rt-priority", std::to_string(plan.rt_priority)});
      if (spin > 0 && unset("--spin-us")) argv->insert(argv->end(), {"--spin-us", std::to_string(spin)});
    }
    std::vector<std::string> spawner{"spawner"};
    spawner.insert(spawner.end(), plan.controllers.begin(), plan.controllers.end());
    spawner.insert(spawner.end(), {"--shutdown-timeout", fmt::format("{:g}", stop_timeout * 0.3)});
    if (plan.sim && plan.mode == "lockstep") spawner.push_back("--hardware-later");  // the sim starts after it
    spawner.insert(spawner.end(), plan.spawner_args.begin(), plan.spawner_args.end());
    std::vector<std::string> rsp{"state-publisher", "--urdf", plan.urdf, "--config", plan.config};
    rsp.insert(rsp.end(), file_args.begin(), file_args.end());
    std::vector<std::string> dash{"dashboard", "--urdf", plan.urdf, "--port", std::to_string(dashboard_port)};
    dash.insert(dash.end(), urdf_args.begin(), urdf_args.end());

    if (dry_run) {
      if (plan.sim) fmt::print("{}: {}\n", plan.sim_name, fmt::join(with_ns(sim, ns), " "));
      if (plan.controller_manager) fmt::print("{}: {}\n", plan.cm_name, fmt::join(with_ns(cm, ns), " "));
      if (plan.state_publisher) fmt::print("{}: {}\n", plan.state_publisher_name, fmt::join(with_ns(rsp, ns), " "));
      if (dashboard) fmt::print("dashboard: {}\n", fmt::join(with_ns(dash, ns), " "));
      for (const auto& p : plan.processes)
        fmt::print("{}: {}{}\n", p.name, fmt::join(p.argv, " "), p.required ? " (required)" : "");
      if (!plan.controllers.empty()) fmt::print("{}: {}\n", plan.spawner_name, fmt::join(with_ns(spawner, ns), " "));
      for (const auto& c : plan.commands)
        fmt::print("command source: {} [{}] rate {:g} count {} duration {:g}\n", c.target, fmt::join(c.expr, ", "),
                   c.rate, c.count, c.duration);
      return int(kExitOk);
    }

    install_stop_signals();
    auto bus = std::make_unique<Bus>(bus_flags.lcm_url, ns, hw_url);
    std::vector<std::pair<std::string, std::string>> env{{"LCM_DEFAULT_URL", bus->url()}};
    if (!package_path.empty()) env.emplace_back("LCM_CONTROL_PACKAGE_PATH", fmt::format("{}", fmt::join(package_path, ":")));
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
          bus->channel(channels::kCmResponse), where,
          probe->manager_message()));
    if (plan.sim && probe->hardware_seen())
      throw std::runtime_error(fmt::format(
          "hardware already publishes '{}' in {}: a second simulator there would make two sessions the controller "
          "manager cannot both follow. Stop it, or launch this robot with --namespace NAME or another --lcm-url",
          bus->channel(channels::kHardwareState), where));
    Child *sim_c = nullptr, *cm_c = nullptr, *spawner_c = nullptr;
    std::vector<Child*> others;
    std::string failure;

    const int64_t up_deadline = monotonic_us() + int64_t(ready_timeout * 1e6);
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
      failure = fmt::format("not up within {}: {}", seconds_text(ready_timeout), fmt::join(waiting, ", "));
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
      if (dashboard) others.push_back(&sup.start("dashboard", with_ns(dash, ns), false));
      if (!plan.controllers.empty()) {
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
          say(r.message);
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
      say(fmt::format("up: {}{} (Ctrl-C to stop)", plan.controllers.empty() ? "no controllers" : "controllers ",
                      fmt::join(plan.controllers, ", ")));
      sup.wait_until(broken, 1e12);
    }
    std::string why = failure;
    if (why.empty()) why = sup.reason_to_stop();
    if (why.empty() && stop_requested()) why = fmt::format("got {}", strsignal(stop_signal()));
    clear_stop();
    say(fmt::format("stopping ({})", why));

    // Controllers first, then the helpers, then the controller manager and the sim.
    const int64_t t0 = monotonic_us(), budget = int64_t(stop_timeout * 1e6);
    if (spawner_c) sup.stop({spawner_c}, t0 + budget / 2);
    sup.stop(others, t0 + budget * 7 / 10);
    std::vector<Child*> servers;
    if (cm_c) servers.push_back(cm_c);
    if (sim_c) servers.push_back(sim_c);
    sup.stop(servers, t0 + budget);

    std::vector<std::string> failed;
    for (const auto& c : sup.children())
      if (!c->clean()) failed.push_back(Supervisor::exit_text(*c));
    say(fmt::format("all {} processes stopped in {:.2f} s", sup.children().size(), double(monotonic_us() - t0) / 1e6));
    if (!failure.empty()) throw std::runtime_error(failure);
    if (!failed.empty()) throw std::runtime_error(fmt::format("{}", fmt::join(failed, "; ")));
    return int(kExitOk);
  });
}
