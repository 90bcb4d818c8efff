// launch --robots / `robots:`: one launch of the file per robot, in its namespace, supervised as one: up when all
// are, stopped together when one fails or on Ctrl-C.
#include <fmt/ranges.h>

#include <algorithm>
#include <cstring>

#include "tools/lib/launch/launcher.hpp"
#include "tools/lib/launch/supervisor.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {
namespace {

// The flags each robot's launch gets: launch's own, but --robots, --namespace and --dashboard.
std::vector<std::string> passed_flags(const LaunchOptions& o, const LaunchPlan& plan) {
  std::vector<std::string> args;
  auto pass = [&](const char* flag, const std::string& value) {
    if (!value.empty()) args.insert(args.end(), {flag, value});
  };
  pass("--mode", o.mode);
  if (o.paused) args.push_back("--paused");
  pass("--cpu", o.cpu);
  if (o.rt_priority >= 0) pass("--rt-priority", std::to_string(o.rt_priority));
  if (o.spin_us >= 0) pass("--spin-us", std::to_string(o.spin_us));
  pass("--ready-timeout", fmt::format("{:g}", o.ready_timeout));
  pass("--stop-timeout", fmt::format("{:g}", o.stop_timeout));
  if (o.duration > 0) pass("--duration", fmt::format("{:g}", o.duration));
  if (!o.package_path.empty()) pass("--package-path", fmt::format("{}", fmt::join(o.package_path, ":")));
  for (const auto& a : o.xacro_args) pass("--xacro-arg", a);
  for (const auto& a : o.args) pass("--arg", a);
  if (o.file.empty()) {  // the robot from the flags (plan_from_flags), with the controllers it chose
    pass("--urdf", o.urdf);
    for (const auto& c : o.configs) pass("--config", c);
    if (!plan.controllers.empty()) pass("--controllers", fmt::format("{}", fmt::join(plan.controllers, ",")));
    if (!plan.inactive.empty()) pass("--inactive", fmt::format("{}", fmt::join(plan.inactive, ",")));
  }
  pass("--lcm-url", o.bus.lcm_url);
  const std::string hw = !o.bus.hardware_lcm_url.empty()  ? o.bus.hardware_lcm_url
                         : !plan.hardware_lcm_url.empty() ? plan.hardware_lcm_url
                                                          : "auto";
  pass("--hardware-url", hw);
  if (!plan.ns.empty() || !o.bus.ns.empty())
    launch_say(fmt::format("note: the robots' namespaces ({}) replace namespace '{}'", fmt::join(plan.robots, ", "),
                           o.bus.ns.empty() ? plan.ns : o.bus.ns));
  return args;
}

}  // namespace

int run_robots(const LaunchOptions& o, const LaunchPlan& plan) {
  const std::vector<std::string> args = passed_flags(o, plan);
  const std::string url = effective_url(o.bus.lcm_url);
  std::vector<std::vector<std::string>> argvs;
  for (const auto& r : plan.robots) {
    std::vector<std::string> argv{"launch"};
    if (!o.file.empty()) argv.push_back(o.file);
    argv.insert(argv.end(), {"--namespace", r});
    argv.insert(argv.end(), args.begin(), args.end());
    argvs.push_back(argv);
  }
  if (o.dry_run) {
    for (size_t i = 0; i < plan.robots.size(); ++i) fmt::print("{}: {}\n", plan.robots[i], fmt::join(argvs[i], " "));
    return int(kExitOk);
  }
  install_stop_signals();
  std::vector<std::pair<std::string, std::string>> env{{"LCM_DEFAULT_URL", url}};
  if (!o.package_path.empty())
    env.emplace_back("LCM_CONTROL_PACKAGE_PATH", fmt::format("{}", fmt::join(o.package_path, ":")));
  Supervisor sup(env);
  std::vector<Child*> children;
  for (size_t i = 0; i < plan.robots.size(); ++i)
    children.push_back(&sup.start(plan.robots[i], argvs[i], true, "[launch] up: "));
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
  const bool up =
      sup.wait_until([&] { return broken() || all(&Child::ready) || all(&Child::exited); }, o.ready_timeout + 5);
  std::string failure;
  if (!up) {
    std::vector<std::string> waiting;
    for (const Child* c : children)
      if (!c->ready) waiting.push_back(c->name);
    failure = fmt::format("not up within {}: {}", seconds_text(o.ready_timeout + 5), fmt::join(waiting, ", "));
  }
  if (failure.empty() && !broken()) {
    std::vector<std::string> partial;  // robots up without some of their controllers (their launch says which)
    for (const Child* c : children)
      if (c->ready_line.find("FAILED to spawn") != std::string::npos) partial.push_back(c->name);
    launch_say(fmt::format("up: {} robots ({}){} (Ctrl-C to stop)", plan.robots.size(), fmt::join(plan.robots, ", "),
                           partial.empty() ? "" : fmt::format("; controllers FAILED to spawn on {}",
                                                              fmt::join(partial, ", "))));
    sup.wait_until([&] { return broken() || all(&Child::exited); }, 1e12);
  }
  std::string why = failure;
  if (why.empty()) why = failed();
  if (why.empty() && all(&Child::exited)) why = "every robot's launch ended";
  if (why.empty() && stop_requested()) why = fmt::format("got {}", strsignal(stop_signal()));
  clear_stop();
  launch_say(fmt::format("stopping ({})", why));
  const int64_t t0 = monotonic_us();
  sup.stop(children, t0 + int64_t((o.stop_timeout + 2) * 1e6));
  std::vector<std::string> unclean;
  for (const auto& c : sup.children())
    if (!c->clean()) unclean.push_back(Supervisor::exit_text(*c));
  launch_say(fmt::format("all {} robots stopped in {:.2f} s", children.size(), double(monotonic_us() - t0) / 1e6));
  if (!failure.empty()) throw std::runtime_error(failure);
  if (!unclean.empty()) throw std::runtime_error(fmt::format("{}", fmt::join(unclean, "; ")));
  return int(kExitOk);
}

}  // namespace lcm_control::tools
