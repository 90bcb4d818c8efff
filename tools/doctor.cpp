// doctor: loads a URDF and a ros_control YAML the way sim_server and
// controller_manager will, tries every configured controller exactly as
// controller_manager's load would (in-process, no bus), and prints what it
// resolved, or every problem. Exit 3 when the servers would refuse the files,
// a controller would be refused, or no controller is configured.
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>

#include "cli/cli.hpp"
#include "tools/model_report.hpp"
#include "description/model_check.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "controller_manager/manager.hpp"
#include "controller_manager/plugins.hpp"
#include "controllers/builtin.hpp"

namespace {

using lcm_control::cm::ControllerCheck;

const char* verdict(ControllerCheck::Outcome o) {
  switch (o) {
    case ControllerCheck::Loads: return "loads";
    case ControllerCheck::NotImplemented: return "not available here";
    case ControllerCheck::InterfaceMismatch: return "will not load with this URDF's transmissions";
    case ControllerCheck::Refused: return "REFUSED";
  }
  return "?";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Check a URDF + ros_control YAML and print the robot model as the servers will use it; every configured "
      "controller is loaded in-process as controller_manager would load it.\n"
      "Example: doctor --urdf config/turret_bot.urdf --config config/turret_bot.yaml",
      "doctor"};
  std::string urdf;
  std::vector<std::string> config;
  std::vector<std::string> package_path, args;
  BusFlags bus_flags;
  bool strict = false;
  app.add_option("--urdf", urdf, "URDF file (or .urdf.xacro, with --xacro-arg) with <transmission> tags")->required();
  add_config_flag(app, config, "ros_control YAML (controllers, gazebo_ros_control/pid_gains)");
  app.add_option("--namespace", bus_flags.ns,
                 "the robot's namespace (default: $LCM_CONTROL_NAMESPACE, else the gazebo_ros_control plugin's "
                 "<robotNamespace>); the YAML is read under it when it nests there")
      ->envname(kNamespaceEnv);
  app.add_flag("--strict", strict, "treat warnings as errors (exit 3)");
  add_package_path_flag(app, package_path);
  add_arg_flag(app, args);
  std::vector<std::string> xacro_args;
  add_xacro_arg_flag(app, xacro_args);
  std::vector<std::string> simulate_hardware;
  add_simulate_hardware_flag(app, simulate_hardware);
  std::vector<std::string> to_start;
  app.add_option("--controllers", to_start,
                 "the controllers that will be started (a,b; the spawner's list): one of them that cannot load is an "
                 "error; any other that cannot (another package's type, another variant of the robot) a warning")
      ->delimiter(',');
  return run_program(app, argc, argv, [&] {
    LoadOptions options = load_options(package_path, bus_flags, args, xacro_args, simulate_hardware);
    options.config_from_plugin = true;
    const RobotModel model = load_robot_model(urdf, config, options);
    std::fputs(describe(model).c_str(), stdout);
    for (const auto& n : model.notes) std::printf("note: %s\n", n.c_str());

    std::vector<std::string> errors, warnings = model.warnings;
    if (const std::string why = simulation_size_problem(model); !why.empty()) errors.push_back(why);
    size_t loadable = 0;
    // What launch and controller_manager would load: --config's YAML, or the one the URDF's gz plugin names in its
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
      for (const auto& c : checks) {
        std::printf("  %-32s %s\n", c.name.c_str(), verdict(c.outcome));
        const bool started = std::find(to_start.begin(), to_start.end(), c.name) != to_start.end();
        if (c.outcome == ControllerCheck::Loads) ++loadable;
        if (c.outcome == ControllerCheck::Refused) errors.push_back(c.message);
        if (c.outcome == ControllerCheck::NotImplemented || c.outcome == ControllerCheck::InterfaceMismatch)
          (started ? errors : warnings).push_back(started ? c.message + " (and --controllers starts it)" : c.message);
        warnings.insert(warnings.end(), c.notes.begin(), c.notes.end());
      }
      for (const auto& name : to_start)
        if (!model.controller(name))
          errors.push_back(fmt::format("--controllers {}: {} configures no controller '{}' (configured: {})", name,
                                       model.config_path, name, [&] {
                                         std::string all;
                                         for (const auto& c : model.controllers)
                                           all += (all.empty() ? "" : ", ") + c.name;
                                         return all.empty() ? std::string("none") : all;
                                       }()));
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
      return int(kExitBadInput);
    }
    std::printf("\nOK: %zu joints, %zu transmissions, %zu controllers", model.joints.size(),
                model.transmissions.size(), model.controllers.size());
    if (!model.config_path.empty() && loadable != model.controllers.size())
      std::printf(" (%zu load with this URDF, %zu %s not: see the warnings)", loadable,
                  model.controllers.size() - loadable, model.controllers.size() - loadable == 1 ? "does" : "do");
    std::printf("\n");
    return int(kExitOk);
  });
}
