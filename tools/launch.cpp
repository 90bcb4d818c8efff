// launch: roslaunch for lcm_control. Starts sim_server and controller_manager
// from a YAML or ROS XML launch file, waits until both answer, spawns the
// controllers, registers the file's command sources, prefixes every child's
// output with its name, and stops everything in order (controllers, then
// processes) on Ctrl-C, a death, or when sim_server ends its --duration. In
// lockstep, sim_server starts last, so controllers and command sources start at
// step 0 in every run.
#include "cli/cli.hpp"
#include "tools/lib/launch/launcher.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Start sim_server and controller_manager from one launch file, wait until both answer, spawn the controllers, "
      "and stop everything in order on Ctrl-C or when a process dies (exit 1 if one failed, 3 if one refused a bad "
      "file). Reads our YAML launch files and ROS launch XML (gazebo_ros_control.launch: <param textfile>, <rosparam load>, $(find PKG), the "
      "spawner's args; gazebo -> sim_server, robot_state_publisher -> state-publisher). Children get "
      "LCM_DEFAULT_URL; every output line is prefixed with the child's name.\n"
      "Examples:\n"
      "  launch config/turret_bot.launch.yaml\n"
      "  launch ~/catkin_ws/src/turret_bot/launch/gazebo_ros_control.launch --package-path ~/catkin_ws/src\n"
      "  launch config/turret_bot.launch.yaml --mode lockstep --dry-run\n"
      "  launch config/turret_bot_demo.launch.yaml --duration 20       # lockstep demo, exits when done\n"
      "  launch --urdf config/turret_bot.urdf --config config/turret_bot.yaml   # no launch file: every controller\n"
      "  launch --urdf R.urdf --config C.yaml --controllers joint_state_controller,arm_controller\n"
      "In lockstep mode the controller manager starts first, the controllers are spawned and the file's commands "
      "registered as command sources, and only then sim_server starts: every run is the same from step 0.",
      "launch"};
  LaunchCommand command;
  add_launch_flags(app, command);
  return run_program(app, argc, argv, [&] { return run_launch_command(command); });
}
