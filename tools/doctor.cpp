// doctor: loads a URDF and a ros_control YAML the way sim_server and
// controller_manager will, and prints what it resolved (or every problem).
#include "common/cli.hpp"
#include "common/robot_model.hpp"

#include <cstdio>

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Check a URDF + ros_control YAML and print the robot model as the servers will use it.\n"
      "Example: doctor --urdf config/turret_bot.urdf --config config/turret_bot.yaml",
      "doctor"};
  std::string urdf, config;
  std::vector<std::string> package_path;
  bool strict = false;
  app.add_option("--urdf", urdf, "URDF file with <transmission> tags")->required();
  app.add_option("--config", config, "ros_control YAML (controllers, gazebo_ros_control/pid_gains)");
  app.add_flag("--strict", strict, "treat warnings as errors (exit 3)");
  add_package_path_flag(app, package_path);
  return run_program(app, argc, argv, [&] {
    const RobotModel model = load_robot_model(urdf, config, LoadOptions{package_path});
    std::fputs(describe(model).c_str(), stdout);
    if (strict && !model.warnings.empty()) {
      for (const auto& w : model.warnings) std::fprintf(stderr, "doctor: error: %s\n", w.c_str());
      return int(kExitBadInput);
    }
    std::printf("\nOK: %zu joints, %zu transmissions, %zu controllers\n", model.joints.size(),
                model.transmissions.size(), model.controllers.size());
    return int(kExitOk);
  });
}
