#include "tools/lib/launch/launcher.hpp"

namespace lcm_control::tools {

void add_launch_flags(CLI::App& app, LaunchCommand& c) {
  app.add_option("FILE", c.positional,
                 "launch file: YAML (see config/turret_bot.launch.yaml) or ROS launch XML, then NAME:=VALUE for its "
                 "<arg>s as roslaunch takes them (the same as --arg NAME=VALUE)");
  app.add_option("--urdf", c.options.urdf,
                 "without a FILE: the robot (.urdf or .xacro) to start with sim_server, controller_manager and a "
                 "spawner, as a launch file with only urdf:, config: and controllers: would");
  add_config_flag(app, c.options.configs,
                  "with --urdf: the controllers YAML; --controllers defaults to every controller it configures");
  add_arg_flag(app, c.options.args);
  app.add_option("--mode", c.options.mode, "override the file's mode: realtime or lockstep")
      ->check(CLI::IsMember({"realtime", "lockstep"}));
  app.add_flag("--paused", c.options.paused,
               "start sim_server paused (Gazebo's paused:=true): controllers are spawned, nothing moves until "
               "`cmctl resume`");
  auto* fixed_flag = app.add_flag("--fixed-base", c.fixed_base,
                                  "weld the robot's root link to the world where it starts, even when the URDF has no "
                                  "joint to `world` (default: free on the ground, as Gazebo spawns it)");
  app.add_flag("--floating-base", c.floating_base, "the root link is free even if the file says base: fixed")
      ->excludes(fixed_flag);
  app.add_flag("--physics", c.options.physics,
               "sim_server simulates the robot in Bullet even when its <ros2_control> blocks name mock hardware (a "
               "demo's mock-like plugin, mock_components)");
  app.add_option("--cpu", c.options.cpu,
                 "override the file's cpu: auto (lockstep: sim_server and controller_manager share the least busy "
                 "CPU), none, or a CPU number")
      ->check([](const std::string& v) { return check_cpu(v); });
  app.add_option("--rt-priority", c.options.rt_priority,
                 "run sim_server and controller_manager at SCHED_FIFO with this priority (1-99) and memory locked, "
                 "and in real time let each spin the last --spin-us before its deadline; 0: the normal scheduler "
                 "(overrides the file's rt_priority; needs root, CAP_SYS_NICE or `ulimit -r`)")
      ->check(CLI::Range(0, kMaxRtPriority));
  app.add_option("--spin-us", c.options.spin_us,
                 fmt::format("microseconds each loop process spins before its real-time deadline instead of "
                             "sleeping (default {} with --rt-priority, else 0; overrides the file's spin_us)",
                             kRealTimeSpinUs))
      ->check(CLI::Range(0, kMaxSpinUs));
  app.add_option("--ready-timeout", c.options.ready_timeout, "seconds for the servers and the spawner to come up")
      ->check(CLI::PositiveNumber);
  app.add_option("--stop-timeout", c.options.stop_timeout, "seconds for everything to stop before the rest is killed")
      ->check(CLI::PositiveNumber);
  app.add_option("--duration", c.options.duration,
                 "sim seconds: passed to sim_server, which stops then; launch then stops the rest and exits 0")
      ->check(CLI::PositiveNumber);
  app.add_flag("--dry-run", c.options.dry_run, "print what would be started and exit");
  app.add_option("--controllers", c.options.controllers,
                 "controllers to start (a,b,c), instead of the file's `controllers:` (ROS 2's spawner calls)")
      ->delimiter(',');
  app.add_option("--inactive", c.options.inactive, "controllers to load without starting (a,b; ROS 2's spawner --inactive)")
      ->delimiter(',');
  add_package_path_flag(app, c.options.package_path);
  app.get_option("--package-path")->allow_extra_args(false);  // NAME:=VALUE after it stays an argument
  add_xacro_arg_flag(app, c.options.xacro_args);
  add_simulate_hardware_flag(app, c.options.simulate_hardware);
  add_bus_flags(app, c.options.bus);
  add_hardware_url_flag(app, c.options.bus);
  add_hardware_mirror_flag(app, c.options.bus);
  app.add_option("--robots", c.options.robots,
                 "start this many copies of the robot, in namespaces r0, r1, ..., each with its hardware loop on its "
                 "own port (--hardware-url auto unless given; `shared` keeps them on the --lcm-url); overrides "
                 "the file's `robots:`")
      ->check(CLI::Range(1, kMaxRobots));
  app.add_flag("--dashboard", c.options.dashboard,
               "also start the dashboard (the robot in a browser: plots, sliders, gains, controllers) once the "
               "servers are up, and print its URL");
  app.add_option("--dashboard-port", c.options.dashboard_port, "the dashboard's port (default 8080; 0: one the system picks)")
      ->check(CLI::Range(0, 65535));
}

void take_launch_arguments(LaunchOptions& o, const std::vector<std::string>& positional) {
  for (const std::string& p : positional) {
    if (p.find(":=") != std::string::npos)
      o.args.push_back(p);
    else if (o.file.empty())
      o.file = p;
    else
      throw CLI::ValidationError("FILE", "one launch file, then NAME:=VALUE arguments; got '" + o.file + "' and '" +
                                             p + "'");
  }
}

int run_launch_command(LaunchCommand c) {
  LaunchOptions& o = c.options;
  take_launch_arguments(o, c.positional);
  o.base = c.fixed_base ? "fixed" : c.floating_base ? "floating" : "";
  return run_launch(o);
}

}  // namespace lcm_control::tools
