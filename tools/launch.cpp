// launch: roslaunch for lcm_control. Starts sim_server and controller_manager
// from a YAML or ROS XML launch file, waits until both answer, spawns the
// controllers, prefixes every child's output with its name, and stops
// everything in order (controllers, then processes) on Ctrl-C or a death.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/ranges.h>

#include "common/cli.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "tools/launch_file.hpp"
#include "tools/support.hpp"

namespace lcm_control::tools {
namespace {

struct Child {
  std::string name;
  std::vector<std::string> argv;
  bool required = true;
  pid_t pid = -1;
  int fd = -1;
  std::string partial;
  bool ready = false;    // printed a line with " ready"
  bool exited = false;
  bool signalled = false;  // we asked it to stop
  bool killed = false;     // we had to SIGKILL it
  int code = 0;            // exit code, or 128 + signal
  bool clean() const { return code == 0 || (signalled && !killed && (code == 128 + SIGINT || code == 128 + SIGTERM)); }
};

void say(const std::string& line) {
  fmt::print("[launch] {}\n", line);
  std::fflush(stdout);
}

class Supervisor {
 public:
  Supervisor(Bus* bus, std::vector<std::pair<std::string, std::string>> env) : bus_(bus), env_(std::move(env)) {
    exe_dir_ = std::filesystem::read_symlink("/proc/self/exe").parent_path().string();
    state_sub_ = bus_->lcm().subscribe(bus_->channel(channels::kHardwareState), &Supervisor::on_state, this);
    bus_->lcm().subscribe(bus_->channel(channels::kCmResponse), &Supervisor::on_cm, this);
  }
  // Once everything is up launch needs no bus; the caller then closes it (a
  // udpm socket receives every message, which costs CPU the simulation could use).
  void drop_bus() { bus_ = nullptr; }

  Child& start(const std::string& name, std::vector<std::string> argv, bool required) {
    auto c = std::make_unique<Child>();
    c->name = name;
    c->required = required;
    if (argv[0].find('/') == std::string::npos && std::filesystem::exists(exe_dir_ + "/" + argv[0]))
      argv[0] = exe_dir_ + "/" + argv[0];
    c->argv = argv;
    int fds[2];
    if (pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
    std::vector<char*> args;
    for (auto& a : c->argv) args.push_back(a.data());
    args.push_back(nullptr);
    const pid_t parent = getpid();
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
    if (pid == 0) {
      setpgid(0, 0);  // the terminal's Ctrl-C goes to launch only; launch stops children in order
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(127);
      ::signal(SIGINT, SIG_DFL);
      ::signal(SIGTERM, SIG_DFL);
      const int devnull = open("/dev/null", O_RDONLY);
      dup2(devnull, 0);
      dup2(fds[1], 1);
      dup2(fds[1], 2);
      for (const auto& [k, v] : env_) setenv(k.c_str(), v.c_str(), 1);
      execvp(args[0], args.data());
      std::fprintf(stderr, "cannot start %s: %s\n", args[0], std::strerror(errno));
      _exit(127);
    }
    close(fds[1]);
    fcntl(fds[0], F_SETFL, O_NONBLOCK);
    c->pid = pid;
    c->fd = fds[0];
    say(fmt::format("started {} (pid {}): {}", name, pid, fmt::join(c->argv, " ")));
    children_.push_back(std::move(c));
    return *children_.back();
  }

  // Reads output, LCM and exits for up to timeout_ms.
  void pump(int timeout_ms) {
    std::vector<pollfd> pfds;
    std::vector<Child*> owners;
    for (auto& c : children_)
      if (c->fd >= 0) {
        pfds.push_back({c->fd, POLLIN, 0});
        owners.push_back(c.get());
      }
    if (bus_) pfds.push_back({bus_->lcm().getFileno(), POLLIN, 0});
    poll(pfds.data(), pfds.size(), timeout_ms);
    for (size_t k = 0; k < owners.size(); ++k)
      if (pfds[k].revents) read_output(*owners[k]);
    if (bus_ && (pfds.back().revents & POLLIN))
      for (int n = 0; n < 100 && bus_->lcm().handleTimeout(0) > 0; ++n) {
      }
    if (bus_ && state_seen_ && state_sub_) {  // one hardware/state is all launch needs
      bus_->lcm().unsubscribe(state_sub_);
      state_sub_ = nullptr;
    }
    for (auto& c : children_) reap(*c, false);
  }

  // Pumps until pred() or timeout_s; false on timeout.
  template <class Pred>
  bool wait_until(Pred&& pred, double timeout_s) {
    const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
    while (!pred()) {
      if (monotonic_us() >= end) return false;
      pump(20);
    }
    return true;
  }

  // The first required child that exited, or a stop request: why to shut down.
  std::string reason_to_stop() const {
    for (const auto& c : children_)
      if (c->exited && !c->signalled && c->required) return exit_text(*c);
    return "";
  }

  void send_signal(Child& c, int sig) {
    if (c.exited) return;
    c.signalled = true;
    if (kill(-c.pid, sig) != 0) kill(c.pid, sig);
  }

  bool all_exited(const std::vector<Child*>& cs) const {
    for (auto* c : cs)
      if (!c->exited) return false;
    return true;
  }

  // SIGINT to the group, wait until the deadline, then SIGKILL.
  void stop(const std::vector<Child*>& cs, int64_t deadline_us) {
    for (auto* c : cs) send_signal(*c, SIGINT);
    wait_until([&] { return all_exited(cs); }, double(deadline_us - monotonic_us()) / 1e6);
    for (auto* c : cs)
      if (!c->exited) {
        say(fmt::format("{} (pid {}) did not stop in time: killing it", c->name, c->pid));
        c->killed = true;
        kill(-c->pid, SIGKILL);
        kill(c->pid, SIGKILL);
      }
    for (auto* c : cs) reap(*c, true);
  }

  // Sends LIST every 0.5 s until the controller manager answers.
  void poll_manager() {
    if (cm_answered_ || !bus_) return;
    const int64_t now = monotonic_us();
    if (now - last_list_us_ < 500000) return;
    last_list_us_ = now;
    cm_request_t r{};
    r.utime = wall_us();
    r.request_id = list_id_ = new_request_id();
    r.client = "launch";
    r.op = cm_request_t::LIST;
    r.strictness = cm_request_t::STRICT;
    bus_->publish(channels::kCmRequest, r);
  }
  bool manager_answered() const { return cm_answered_; }
  bool hardware_seen() const { return state_seen_; }
  std::vector<std::unique_ptr<Child>>& children() { return children_; }

  static std::string exit_text(const Child& c) {
    if (c.killed) return fmt::format("{} was killed after the stop timeout", c.name);
    if (c.code > 128) return fmt::format("{} died of signal {} ({})", c.name, c.code - 128, strsignal(c.code - 128));
    return fmt::format("{} exited with code {}", c.name, c.code);
  }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&) { state_seen_ = true; }
  void on_cm(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    cm_response_t m;
    if (m.decode(rbuf->data, 0, int(rbuf->data_size)) >= 0 && m.request_id == list_id_) cm_answered_ = true;
  }

  void read_output(Child& c) {
    char buf[4096];
    for (;;) {
      const ssize_t n = read(c.fd, buf, sizeof buf);
      if (n > 0) {
        c.partial.append(buf, size_t(n));
        size_t nl;
        while ((nl = c.partial.find('\n')) != std::string::npos) {
          print_line(c, c.partial.substr(0, nl));
          c.partial.erase(0, nl + 1);
        }
        continue;
      }
      if (n == 0 || (errno != EAGAIN && errno != EINTR)) {
        if (!c.partial.empty()) print_line(c, c.partial);
        c.partial.clear();
        close(c.fd);
        c.fd = -1;
      }
      return;
    }
  }
  // "[name] line", without repeating a "[name]" or "program: " the line already starts with.
  void print_line(Child& c, std::string line) {
    if (line.find(" ready") != std::string::npos || line.rfind("ready", 0) == 0) c.ready = true;
    const std::string prefix = "[" + c.name + "]";
    const std::string program = std::filesystem::path(c.argv[0]).filename().string() + ": ";
    if (line.rfind(program, 0) == 0) line.erase(0, program.size());
    if (line.rfind(prefix, 0) == 0)
      fmt::print("{}\n", line);
    else
      fmt::print("{} {}\n", prefix, line);
    std::fflush(stdout);
  }
  void reap(Child& c, bool block) {
    if (c.exited) return;
    int st = 0;
    const pid_t r = waitpid(c.pid, &st, block ? 0 : WNOHANG);
    if (r != c.pid) return;
    if (c.fd >= 0) read_output(c);
    c.exited = true;
    c.code = WIFEXITED(st) ? WEXITSTATUS(st) : 128 + WTERMSIG(st);
    if (!c.clean() || !c.signalled) say(exit_text(c));
  }

  Bus* bus_;
  lcm::Subscription* state_sub_ = nullptr;
  std::vector<std::pair<std::string, std::string>> env_;
  std::string exe_dir_;
  std::vector<std::unique_ptr<Child>> children_;
  bool state_seen_ = false, cm_answered_ = false;
  int64_t list_id_ = 0, last_list_us_ = 0;
};

std::vector<std::string> with_ns(std::vector<std::string> argv, const std::string& ns) {
  if (!ns.empty()) {
    argv.push_back("--namespace");
    argv.push_back(ns);
  }
  return argv;
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
      "  launch config/turret_bot.launch.yaml --mode lockstep --dry-run",
      "launch"};
  std::string file, mode;
  std::vector<std::string> package_path;
  double ready_timeout = 20, stop_timeout = 5;
  bool dry_run = false;
  BusFlags bus_flags;
  app.add_option("FILE", file, "launch file: YAML (see config/turret_bot.launch.yaml) or ROS launch XML")->required();
  app.add_option("--mode", mode, "override the file's mode: realtime or lockstep")
      ->check(CLI::IsMember({"realtime", "lockstep"}));
  app.add_option("--ready-timeout", ready_timeout, "seconds for the servers and the spawner to come up")
      ->check(CLI::PositiveNumber);
  app.add_option("--stop-timeout", stop_timeout, "seconds for everything to stop before the rest is killed")
      ->check(CLI::PositiveNumber);
  app.add_flag("--dry-run", dry_run, "print what would be started and exit");
  add_package_path_flag(app, package_path);
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&]() -> int {
    LaunchPlan plan = read_launch_file(file, package_path);
    if (!mode.empty()) plan.mode = mode;
    for (const auto& n : plan.notes) say("note: " + n);

    const std::string ns = bus_flags.ns;
    std::vector<std::string> sim{"sim_server", "--urdf", plan.urdf, "--config", plan.config};
    if (plan.mode == "lockstep") sim.push_back("--lockstep");
    if (plan.physics_rate > 0) sim.insert(sim.end(), {"--physics-rate", fmt::format("{:g}", plan.physics_rate)});
    if (plan.control_rate > 0) sim.insert(sim.end(), {"--control-rate", fmt::format("{:g}", plan.control_rate)});
    sim.insert(sim.end(), plan.sim_args.begin(), plan.sim_args.end());
    std::vector<std::string> cm{"controller_manager", "--urdf", plan.urdf, "--config", plan.config};
    cm.insert(cm.end(), plan.cm_args.begin(), plan.cm_args.end());
    std::vector<std::string> spawner{"spawner"};
    spawner.insert(spawner.end(), plan.controllers.begin(), plan.controllers.end());
    spawner.insert(spawner.end(), {"--shutdown-timeout", fmt::format("{:g}", stop_timeout * 0.3)});
    spawner.insert(spawner.end(), plan.spawner_args.begin(), plan.spawner_args.end());
    std::vector<std::string> rsp{"state-publisher", "--urdf", plan.urdf, "--config", plan.config};

    if (dry_run) {
      if (plan.sim) fmt::print("{}: {}\n", plan.sim_name, fmt::join(with_ns(sim, ns), " "));
      if (plan.controller_manager) fmt::print("{}: {}\n", plan.cm_name, fmt::join(with_ns(cm, ns), " "));
      if (plan.state_publisher) fmt::print("{}: {}\n", plan.state_publisher_name, fmt::join(with_ns(rsp, ns), " "));
      for (const auto& p : plan.processes)
        fmt::print("{}: {}{}\n", p.name, fmt::join(p.argv, " "), p.required ? " (required)" : "");
      if (!plan.controllers.empty()) fmt::print("{}: {}\n", plan.spawner_name, fmt::join(with_ns(spawner, ns), " "));
      return int(kExitOk);
    }

    install_stop_signals();
    auto bus = std::make_unique<Bus>(bus_flags.lcm_url, ns);
    std::vector<std::pair<std::string, std::string>> env{{"LCM_DEFAULT_URL", bus->url()}};
    if (!package_path.empty()) env.emplace_back("LCM_CONTROL_PACKAGE_PATH", fmt::format("{}", fmt::join(package_path, ":")));
    Supervisor sup(bus.get(), env);
    Child *sim_c = nullptr, *cm_c = nullptr, *spawner_c = nullptr;
    std::vector<Child*> others;
    std::string failure;

    const int64_t up_deadline = monotonic_us() + int64_t(ready_timeout * 1e6);
    auto left = [&] { return std::max(0.0, double(up_deadline - monotonic_us()) / 1e6); };
    auto broken = [&] { return stop_requested() || !sup.reason_to_stop().empty(); };
    if (plan.sim) sim_c = &sup.start(plan.sim_name, with_ns(sim, ns), true);
    if (plan.controller_manager) cm_c = &sup.start(plan.cm_name, with_ns(cm, ns), true);
    const bool servers_up = sup.wait_until(
        [&] {
          if (cm_c && cm_c->ready) sup.poll_manager();
          return broken() || ((!sim_c || (sim_c->ready && sup.hardware_seen())) &&
                              (!cm_c || (cm_c->ready && sup.manager_answered())));
        },
        left());
    if (!servers_up) {
      std::vector<std::string> waiting;
      if (sim_c && !sim_c->ready) waiting.push_back(plan.sim_name + " (no 'ready' line)");
      if (sim_c && sim_c->ready && !sup.hardware_seen())
        waiting.push_back(fmt::format("{} (nothing on '{}')", plan.sim_name, bus->channel(channels::kHardwareState)));
      if (cm_c && !cm_c->ready) waiting.push_back(plan.cm_name + " (no 'ready' line)");
      if (cm_c && cm_c->ready && !sup.manager_answered())
        waiting.push_back(fmt::format("{} (no answer on '{}')", plan.cm_name, bus->channel(channels::kCmResponse)));
      failure = fmt::format("not up within {}: {}", seconds_text(ready_timeout), fmt::join(waiting, ", "));
    }
    if (failure.empty() && !broken()) {
      sup.drop_bus();
      bus.reset();
      if (plan.state_publisher) others.push_back(&sup.start(plan.state_publisher_name, with_ns(rsp, ns), true));
      for (const auto& p : plan.processes) others.push_back(&sup.start(p.name, p.argv, p.required));
      if (!plan.controllers.empty()) {
        spawner_c = &sup.start(plan.spawner_name, with_ns(spawner, ns), true);
        if (!sup.wait_until([&] { return broken() || spawner_c->ready; }, std::max(left(), 12.0)))
          failure = fmt::format("{} did not report its controllers running within {}", plan.spawner_name,
                                seconds_text(std::max(left(), 12.0)));
      }
    }
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
