// spawner: the controller_manager spawner. Loads controllers, starts them in
// one strict switch, stays running, and stops and unloads them on Ctrl-C. One
// that fails is named with its reason, the others run, and the exit is non-zero.
#include "tools/lib/launch/spawner_program.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Load controllers and start them all in one strict switch (ROS's controller_manager spawner), then stay running; "
      "on Ctrl-C or SIGTERM stop and unload them. A controller that fails to load or start is named with the reason "
      "and the others run, as with ROS's spawner; the ready line names it ('; failed: NAME') and the exit status is "
      "then 1. If none can be spawned (or with --activate-as-group, any), it exits 1 at once with nothing left "
      "loaded. Unlike ROS's, every wait is bounded.\n"
      "Examples:\n"
      "  spawner joint_state_controller j1_controller j2_controller\n"
      "  spawner j2_effort_controller --stopped      # load only; start later with cmctl start\n"
      "  spawner arm_controller --inactive -c /robot1/controller_manager   # ROS 2's flags",
      "spawner"};
  SpawnerFlags flags;
  add_spawner_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_spawner(flags); });
}
