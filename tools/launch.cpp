// launch: roslaunch for lcm_control. Starts sim_server and controller_manager
// from a YAML or ROS XML launch file, waits until both answer, spawns the
// controllers, registers the file's command sources, prefixes every child's
// output with its name, and stops everything in order (controllers, then
// processes) on Ctrl-C, a death, or when sim_server ends its --duration. In
// lockstep, sim_server starts last, so controllers and command sources start at
// step 0 in every run.
#include "cli/cli.hpp"
#include "rt/scheduling.hpp"
#include "tools/lib/launcher.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  LaunchOptions o;
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
  std::vector<std::string> positional;
  app.add_option("FILE", positional,
                 "launch file: YAML (see config/turret_bot.launch.yaml) or ROS launch XML, then NAME:=VALUE for its "
                 "<arg>s as roslaunch takes them (the same as --arg NAME=VALUE)");
  app.add_option("--urdf", o.urdf,
                 "without a FILE: the robot (.urdf or .xacro) to start with sim_server, controller_manager and a "
                 "spawner, as a launch file with only urdf:, config: and controllers: would");
  add_config_flag(app, o.configs,
                  "with --urdf: the controllers YAML; --controllers defaults to every controller it configures");
  add_arg_flag(app, o.args);
  app.add_option("--mode", o.mode, "override the file's mode: realtime or lockstep")
      ->check(CLI::IsMember({"realtime", "lockstep"}));
  app.add_flag("--paused", o.paused,
               "start sim_server paused (Gazebo's paused:=true): controllers are spawned, nothing moves until "
               "`cmctl resume`");
  bool fixed_base = false, floating_base = false;
  auto* fixed_flag = app.add_flag("--fixed-base", fixed_base,
                                  "weld the robot's root link to the world where it starts, even when the URDF has no "
                                  "joint to `world` (default: free on the ground, as Gazebo spawns it)");
  app.add_flag("--floating-base", floating_base, "the root link is free even if the file says base: fixed")
      ->excludes(fixed_flag);
  app.add_flag("--physics", o.physics,
               "sim_server simulates the robot in Bullet even when its <ros2_control> blocks name mock hardware (a "
               "demo's mock-like plugin, mock_components)");
  app.add_option("--cpu", o.cpu,
                 "override the file's cpu: auto (lockstep: sim_server and controller_manager share the least busy "
                 "CPU), none, or a CPU number")
      ->check([](const std::string& v) { return check_cpu(v); });
  app.add_option("--rt-priority", o.rt_priority,
                 "run sim_server and controller_manager at SCHED_FIFO with this priority (1-99) and memory locked, "
                 "and in real time let each spin the last --spin-us before its deadline; 0: the normal scheduler "
                 "(overrides the file's rt_priority; needs root, CAP_SYS_NICE or `ulimit -r`)")
      ->check(CLI::Range(0, kMaxRtPriority));
  app.add_option("--spin-us", o.spin_us,
                 fmt::format("microseconds each loop process spins before its real-time deadline instead of "
                             "sleeping (default {} with --rt-priority, else 0; overrides the file's spin_us)",
                             kRealTimeSpinUs))
      ->check(CLI::Range(0, kMaxSpinUs));
  app.add_option("--ready-timeout", o.ready_timeout, "seconds for the servers and the spawner to come up")
      ->check(CLI::PositiveNumber);
  app.add_option("--stop-timeout", o.stop_timeout, "seconds for everything to stop before the rest is killed")
      ->check(CLI::PositiveNumber);
  app.add_option("--duration", o.duration,
                 "sim seconds: passed to sim_server, which stops then; launch then stops the rest and exits 0")
      ->check(CLI::PositiveNumber);
  app.add_flag("--dry-run", o.dry_run, "print what would be started and exit");
  app.add_option("--controllers", o.controllers,
                 "controllers to start (a,b,c), instead of the file's `controllers:` (ROS 2's spawner calls)")
      ->delimiter(',');
  app.add_option("--inactive", o.inactive, "controllers to load without starting (a,b; ROS 2's spawner --inactive)")
      ->delimiter(',');
  add_package_path_flag(app, o.package_path);
  app.get_option("--package-path")->allow_extra_args(false);  // NAME:=VALUE after it stays an argument
  add_xacro_arg_flag(app, o.xacro_args);
  add_simulate_hardware_flag(app, o.simulate_hardware);
  add_bus_flags(app, o.bus);
  add_hardware_url_flag(app, o.bus);
  add_hardware_mirror_flag(app, o.bus);
  app.add_option("--robots", o.robots,
                 "start this many copies of the robot, in namespaces r0, r1, ..., each with its hardware loop on its "
                 "own port (--hardware-url auto unless given; `shared` keeps them on the --lcm-url); overrides "
                 "the file's `robots:`")
      ->check(CLI::Range(1, kMaxRobots));
  app.add_flag("--dashboard", o.dashboard,
               "also start the dashboard (the robot in a browser: plots, sliders, gains, controllers) once the "
               "servers are up, and print its URL");
  app.add_option("--dashboard-port", o.dashboard_port, "the dashboard's port (default 8080; 0: one the system picks)")
      ->check(CLI::Range(0, 65535));
  return run_program(app, argc, argv, [&] {
    for (const std::string& p : positional) {
      if (p.find(":=") != std::string::npos)
        o.args.push_back(p);
      else if (o.file.empty())
        o.file = p;
      else
        throw CLI::ValidationError("FILE", "one launch file, then NAME:=VALUE arguments; got '" + o.file + "' and '" +
                                               p + "'");
    }
    o.base = fixed_base ? "fixed" : floating_base ? "floating" : "";
    return run_launch(o);
  });
}
