#include "tools/lib/files/doctor.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdio>

#include "controller_manager/manager.hpp"
#include "controller_manager/plugins.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"
#include "description/model_check.hpp"
#include "description/robot_model.hpp"
#include "tools/lib/files/model_report.hpp"
#include "tools/lib/launch/launcher.hpp"

namespace lcm_control::tools {
namespace {

using cm::ControllerCheck;

const char* verdict(ControllerCheck::Outcome o) {
  switch (o) {
    case ControllerCheck::Loads: return "loads";
    case ControllerCheck::NotImplemented: return "not available here";
    case ControllerCheck::InterfaceMismatch: return "will not load with this URDF's transmissions";
    case ControllerCheck::Refused: return "REFUSED";
  }
  return "?";
}

// What doctor checks: the robot's files as read, and the controllers that will be started.
struct Check {
  std::string urdf;
  std::vector<std::string> configs;
  LoadOptions load;
  std::vector<std::string> to_start;
  std::string to_start_source = "--controllers";  // what named them, for the messages
};

int check(const Check& c, bool strict) {
  const RobotModel model = load_robot_model(c.urdf, c.configs, c.load);
  std::fputs(describe(model).c_str(), stdout);
  for (const auto& n : model.notes) std::printf("note: %s\n", n.c_str());

  std::vector<std::string> errors, warnings = model.warnings;
  if (const std::string why = simulation_size_problem(model); !why.empty()) errors.push_back(why);
  size_t loadable = 0;
  // What launch and controller_manager would load: the given YAML, or the one the URDF's gz plugin names in its
  // <parameters> when there is none.
  if (!model.config_path.empty()) {
    if (model.controllers.empty())
      errors.push_back(fmt::format(
          "{}: no controllers found (a controller is a map with a `type:` key, at the top level or under the "
          "robot's namespace{}); see the warnings above for what was read instead",
          model.config_path, model.ns.empty() ? "" : " '" + model.ns + ":'"));
    Bus bus("memq://", model.ns);
    cm::Registry registry = cm::builtin_registry();
    for (const auto& line : cm::load_plugins(registry, cm::plugin_libraries(model))) std::printf("%s\n", line.c_str());
    cm::ControllerManager manager(model, bus, registry);
    const auto checks = manager.check_configured();
    if (!checks.empty()) std::printf("\ncontroller check (as controller_manager would load them):\n");
    for (const auto& k : checks) {
      std::printf("  %-32s %s\n", k.name.c_str(), verdict(k.outcome));
      const bool started = std::find(c.to_start.begin(), c.to_start.end(), k.name) != c.to_start.end();
      if (k.outcome == ControllerCheck::Loads) ++loadable;
      if (k.outcome == ControllerCheck::Refused) errors.push_back(k.message);
      if (k.outcome == ControllerCheck::NotImplemented || k.outcome == ControllerCheck::InterfaceMismatch)
        (started ? errors : warnings)
            .push_back(started ? fmt::format("{} (and {} starts it)", k.message, c.to_start_source) : k.message);
      warnings.insert(warnings.end(), k.notes.begin(), k.notes.end());
    }
    std::vector<std::string> configured;
    for (const auto& k : model.controllers) configured.push_back(k.name);
    for (const auto& name : c.to_start)
      if (!model.controller(name))
        errors.push_back(fmt::format("{} {}: {} configures no controller '{}' (configured: {})", c.to_start_source,
                                     name, model.config_path, name,
                                     configured.empty() ? std::string("none") : fmt::format("{}", fmt::join(configured, ", "))));
  }
  if (warnings.size() > model.warnings.size()) {
    std::printf("\ncontroller warnings (%zu):\n", warnings.size() - model.warnings.size());
    for (size_t k = model.warnings.size(); k < warnings.size(); ++k) std::printf("  %s\n", warnings[k].c_str());
  }
  if (strict)
    for (const auto& w : warnings) errors.push_back("(--strict) " + w);
  if (!errors.empty()) {
    std::fflush(stdout);
    for (const auto& e : errors) std::fprintf(stderr, "doctor: error: %s\n", e.c_str());
    return kExitBadInput;
  }
  std::printf("\nOK: %zu joints, %zu transmissions, %zu controllers", model.joints.size(), model.transmissions.size(),
              model.controllers.size());
  if (!model.config_path.empty() && loadable != model.controllers.size())
    std::printf(" (%zu load with this URDF, %zu %s not: see the warnings)", loadable,
                model.controllers.size() - loadable, model.controllers.size() - loadable == 1 ? "does" : "do");
  std::printf("\n");
  return kExitOk;
}

// The robot `launch FILE NAME:=VALUE...` would start, with the same flags, as launch resolves it.
Check from_launch_file(const DoctorFlags& f) {
  if (!f.files.urdf.empty())
    throw CLI::ValidationError("--urdf", "give a launch FILE or --urdf (with --config), not both");
  if (!f.files.config.empty())
    throw CLI::ValidationError("--config", "goes with --urdf; a launch FILE names its own config");
  LaunchOptions o;
  take_launch_arguments(o, f.positional);
  for (const auto& a : f.files.args) o.args.push_back(a);
  o.package_path = f.files.package_path;
  o.xacro_args = f.files.xacro_args;
  o.simulate_hardware = f.files.simulate_hardware;
  o.bus.ns = f.ns;
  o.controllers = f.to_start;
  const LaunchPlan plan = resolve_launch(o);
  Check c;
  c.urdf = plan.urdf;
  c.configs = plan.configs;
  c.load.package_path = f.files.package_path;
  c.load.ns = !f.ns.empty() ? f.ns : !plan.robots.empty() ? plan.robots.front() : plan.ns;
  c.load.args = plan.args;
  c.load.xacro_args = plan.xacro_args;
  c.load.simulate_hardware = plan.simulate_hardware;
  c.load.config_from_plugin = true;
  c.to_start = plan.controllers;
  c.to_start.insert(c.to_start.end(), plan.inactive.begin(), plan.inactive.end());  // loaded: they must load too
  c.to_start_source = f.to_start.empty() ? o.file : "--controllers";
  std::printf("doctor: what `launch %s` starts: %s%s%s; controllers %s\n", fmt::format("{}", fmt::join(f.positional, " ")).c_str(),
              plan.urdf.c_str(), plan.configs.empty() ? "" : " with ", fmt::format("{}", fmt::join(plan.configs, ", ")).c_str(),
              c.to_start.empty() ? "none" : fmt::format("{}", fmt::join(c.to_start, ", ")).c_str());
  if (!plan.robots.empty())
    std::printf("doctor: %zu robots of these files; checked in the namespace %s\n", plan.robots.size(),
                c.load.ns.c_str());
  return c;
}

}  // namespace

void add_doctor_flags(CLI::App& app, DoctorFlags& f) {
  app.add_option("FILE", f.positional,
                 "a launch file (YAML or ROS launch XML), then NAME:=VALUE for its <arg>s: check what `launch FILE` "
                 "would start, as launch reads it (instead of --urdf and --config)");
  app.add_option("--urdf", f.files.urdf, "URDF file (or .urdf.xacro, with --xacro-arg) with <transmission> tags");
  add_config_flag(app, f.files.config, "ros_control YAML (controllers, gazebo_ros_control/pid_gains)");
  app.add_option("--namespace", f.ns,
                 "the robot's namespace (default: $LCM_CONTROL_NAMESPACE, else the gazebo_ros_control plugin's "
                 "<robotNamespace>); the YAML is read under it when it nests there")
      ->envname(kNamespaceEnv);
  app.add_flag("--strict", f.strict, "treat warnings as errors (exit 3)");
  add_package_path_flag(app, f.files.package_path);
  app.get_option("--package-path")->allow_extra_args(false);  // NAME:=VALUE after it stays an argument
  add_arg_flag(app, f.files.args);
  add_xacro_arg_flag(app, f.files.xacro_args);
  add_simulate_hardware_flag(app, f.files.simulate_hardware);
  app.add_option("--controllers", f.to_start,
                 "the controllers that will be started (a,b; the spawner's list): one of them that cannot load is an "
                 "error; any other that cannot (another package's type, another variant of the robot) a warning")
      ->delimiter(',');
}

int run_doctor(const DoctorFlags& f) {
  if (!f.positional.empty()) return check(from_launch_file(f), f.strict);
  if (f.files.urdf.empty())
    throw CLI::ValidationError("--urdf", "give the robot with --urdf R.urdf (and --config C.yaml), or a launch FILE");
  Check c;
  c.urdf = f.files.urdf;
  c.configs = f.files.config;
  BusFlags bus;
  bus.ns = f.ns;
  c.load = load_options(f.files, bus);
  c.load.config_from_plugin = true;  // the gz plugin's <parameters> when no --config, as launch loads it
  c.to_start = f.to_start;
  return check(c, f.strict);
}

}  // namespace lcm_control::tools
