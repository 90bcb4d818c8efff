// controller_manager: flags, then one call (controller_manager/program.hpp). Loads the URDF and YAML, runs the loop
// on hardware/state, serves requests between cycles a slice at a time, stops and unloads everything on
// SIGINT/SIGTERM. Exit codes: 0 clean stop, 2 usage, 3 bad URDF/YAML, 4 LCM.
#include "controller_manager/program.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "controller_manager: hosts ros_control-style controllers and runs read -> update -> write against "
      "hardware/state and hardware/command on LCM. Controllers are loaded and started by spawner or cmctl.\n"
      "Examples:\n"
      "  controller_manager --urdf config/turret_bot.urdf --config config/turret_bot.yaml\n"
      "  controller_manager --urdf robot.urdf --config robot.yaml --namespace r1 --cpu 1 --rt-priority 80",
      "controller_manager"};
  cm::ProgramFlags flags;
  cm::add_program_flags(app, flags);
  return run_program(app, argc, argv, [&] { return cm::run_controller_manager(flags); });
}
