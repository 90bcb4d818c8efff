// sim_server: the URDF robot in Bullet, playing the hardware over LCM for a
// controller_manager (docs/hardware-protocol.md). Flags and wiring only.
#include <algorithm>
#include <cmath>
#include <optional>

#include "cli/cli.hpp"
#include "rt/log.hpp"
#include "rt/scheduling.hpp"
#include "rt/stop_signal.hpp"
#include "sim_server/sim_io.hpp"
#include "sim_server/simulation.hpp"
#include "sim_server/stepper.hpp"
#include "description/load.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Simulate a URDF robot in Bullet and play its hardware over LCM (hardware/state, hardware/command, clock, "
      "e_stop, sim_server/gains).\n"
      "Example: sim_server --urdf config/turret_bot.urdf --config config/turret_bot.yaml --mode lockstep",
      "sim_server"};
  std::string urdf, log_level;
  std::vector<std::string> config;
  std::vector<std::string> package_path;
  BusFlags bus_flags;
  SchedulingFlags sched;
  sim::SimulationRates rates;
  sim::StepperOptions opt;
  double clock_hz = 100;
  app.add_option("--urdf", urdf, "URDF (or .urdf.xacro, with --xacro-arg) with <transmission> tags")->required();
  add_config_flag(app, config, "ros_control YAML (gazebo_ros_control/pid_gains); none: every joint direct");
  std::string mode = "realtime";
  app.add_option("--mode", mode,
                 "realtime: paced by the wall clock; lockstep: step only when the controller manager answers "
                 "(deterministic, as fast as the two processes go)")
      ->check(CLI::IsMember({"realtime", "lockstep"}))
      ->capture_default_str();
  app.add_option("--physics-rate", rates.physics_hz, "physics steps per second")->capture_default_str();
  app.add_option("--control-rate", rates.control_hz, "hardware state/command exchanges per second (divides "
                                                      "--physics-rate)")
      ->capture_default_str();
  app.add_option("--clock-rate", clock_hz,
                 "sim_clock_t on `clock` this often, in Hz of sim time (nearest whole number of control steps); 0: "
                 "every control step")
      ->capture_default_str();
  app.add_option("--duration", opt.duration_s, "stop after this many seconds of sim time (0: run until stopped)");
  app.add_option("--lockstep-timeout", opt.lockstep_timeout_s,
                 "lockstep: republish the state this often (s) while no command comes")
      ->capture_default_str();
  app.add_option("--watchdog", opt.watchdog_s, "real time: hold every actuator after this long (s) without a command")
      ->capture_default_str();
  std::string overrun = "catch-up";
  app.add_option("--overrun", overrun,
                 "real time, a cycle a period or more late: catch-up runs the steps due back to back, each published "
                 "(the controller gets a burst); skip takes them without publishing and goes on from the newest (the "
                 "controller sees the step jump, counted as missed). Sim time keeps up with the wall clock either way")
      ->check(CLI::IsMember({"catch-up", "skip"}))
      ->capture_default_str();
  app.add_option("--spin-us", opt.spin_us,
                 "real time: sleep until this many microseconds before each deadline, then poll without sleeping "
                 "(a timer wakes late by tens of microseconds; spinning costs this much CPU per period)")
      ->check(CLI::Range(int64_t{0}, int64_t{100000}))
      ->capture_default_str();
  app.add_option("--answer-wait-us", opt.answer_wait_us,
                 "real time: each step is taken when the controller's answer to the state before it arrives and "
                 "its state published on its deadline; this is how long past the deadline the answer is awaited (a "
                 "catch-up burst then still gets a command per step); 0: step when due with the newest command, a "
                 "missed cycle when it is not the answer")
      ->check(CLI::Range(int64_t{0}, int64_t{100000}))
      ->capture_default_str();
  long timer_slack_ns = 50000;
  app.add_option("--timer-slack-ns", timer_slack_ns,
                 "real time: how late the pacing timer may wake (Linux's default for a normal thread: 50000)")
      ->check(CLI::Range(1L, 10000000L))
      ->capture_default_str();
  std::vector<std::string> initial;
  app.add_option("-J,--initial-position", initial,
                 "JOINT=VALUE: start that joint there (rad or m; repeatable), as spawn_model's -J; joints not given "
                 "start at 0, and a start outside the URDF limits is clamped into them")
      ->check(initial_position_problem);
  app.add_flag("--paused", opt.start_paused,
               "start paused, as Gazebo's paused:=true: the state is published and controllers can be spawned, but "
               "nothing steps until `cmctl resume` (or `cmctl step N`)");
  sim::WorldOptions world;
  bool floating = false, fixed = false;
  auto* floating_flag = app.add_flag(
      "--floating-base", floating,
      "the root link is free, even if the URDF names it `world`; its ground truth goes on sim_server/base_pose "
      "(default: free when the URDF has no joint to `world`, as Gazebo spawns it, welded when it has)");
  app.add_flag("--fixed-base", fixed,
               "weld the root link to the world where it starts, even when the URDF has no joint to `world` (an arm "
               "bolted to a table)")
      ->excludes(floating_flag);
  bool ground = false, no_ground = false;
  app.add_flag("--ground", ground, "a ground plane at z = 0 (default with a free base)");
  app.add_flag("--no-ground", no_ground, "no ground plane, even with a free base")->excludes("--ground");
  std::vector<double> base_pose;
  app.add_option("--base-pose", base_pose,
                 "X Y Z YAW: where the root link starts (m, rad; default 0 0 0 0); a free base below the ground is "
                 "lifted onto it")
      ->expected(4);
  std::optional<double> spawn_x, spawn_y, spawn_z, spawn_yaw;
  app.add_option("-x", spawn_x, "the root link's start x (m), as ros_gz_sim create and spawn_model take it")
      ->excludes("--base-pose");
  app.add_option("-y", spawn_y, "its start y (m)")->excludes("--base-pose");
  app.add_option("-z", spawn_z, "its start z (m)")->excludes("--base-pose");
  app.add_option("-Y", spawn_yaw, "its start yaw (rad)")->excludes("--base-pose");
  bool no_brakes = false;
  app.add_flag("--no-brakes", no_brakes,
               "joints nobody commands, or held by the watchdog, are left to their PID (position) or limp (effort, "
               "velocity), as in Gazebo (default: braked where they are)");
  bool mock_hardware = false, physics = false;
  auto* mock_flag = app.add_flag(
      "--mock-hardware", mock_hardware,
      "play the robot without physics, as ros2_control's mock_components/GenericSystem: the state follows "
      "the command (the default when every <ros2_control> block names mock_components/GenericSystem)");
  app.add_flag("--physics", physics,
               "simulate the robot in Bullet even when its <ros2_control> blocks name mock hardware (a description "
               "written for mock_components or a demo's mock-like plugin, run as gz_ros2_control would run it)")
      ->excludes(mock_flag);
  app.add_option("--log-level", log_level, "debug, info, warn or error");
  add_bus_flags(app, bus_flags);
  add_hardware_url_flag(app, bus_flags);
  add_hardware_reader_flag(app, bus_flags);
  add_hardware_mirror_flag(app, bus_flags);
  add_package_path_flag(app, package_path);
  std::vector<std::string> args;
  add_arg_flag(app, args);
  std::vector<std::string> xacro_args;
  add_xacro_arg_flag(app, xacro_args);
  std::vector<std::string> simulate_hardware;
  add_simulate_hardware_flag(app, simulate_hardware);
  add_scheduling_flags(app, sched);

  return run_program(app, argc, argv, [&] {
    opt.lockstep = mode == "lockstep";
    opt.overrun = overrun == "skip" ? sim::Overrun::Skip : sim::Overrun::CatchUp;
    sim::substeps_for(rates);  // bad rates fail before anything else is said
    std::string scheduling = apply_scheduling(sched);
    if (!opt.lockstep) set_timer_slack(timer_slack_ns);
    if (!opt.lockstep && opt.spin_us > 0)
      scheduling += fmt::format("{}spinning {} us before each deadline", scheduling.empty() ? "" : ", ", opt.spin_us);
    setup_logging("sim_server", log_level);
    LoadOptions options = load_options(package_path, bus_flags, args, xacro_args, simulate_hardware);
    options.config_from_plugin = true;
    const RobotModel model = load_robot_model(urdf, config, options);
    for (const auto& n : model.notes) spdlog::info("{}", n);
    for (const auto& w : model.warnings) spdlog::warn("{}", w);
    // A ROS 2 parameter file's update_rate is the control rate (gz_ros2_control runs the manager at it) unless
    // --control-rate says otherwise; the physics rate becomes its nearest multiple at or above 1 kHz if not given.
    if (model.update_rate_hz && app.get_option("--control-rate")->count() == 0) {
      rates.control_hz = *model.update_rate_hz;
      if (app.get_option("--physics-rate")->count() == 0)
        rates.physics_hz = rates.control_hz * std::ceil(1000.0 / rates.control_hz - 1e-9);
      sim::substeps_for(rates);
      spdlog::info("{}: control rate {:g} Hz from controller_manager's update_rate (physics {:g} Hz)",
                   model.config_path, rates.control_hz, rates.physics_hz);
    }
    const int clock_every = sim::clock_every_for(rates.control_hz, clock_hz);
    InitialPositions start = model.initial_positions;  // <ros2_control> initial_value; -J overrides
    for (const auto& a : initial) {
      const auto [joint, q] = parse_initial_position(a);
      start[joint] = q;
    }
    if (base_pose.size() == 4) {
      world.base_position = {base_pose[0], base_pose[1], base_pose[2]};
      world.base_yaw = base_pose[3];
    }
    world.base_position = {spawn_x.value_or(world.base_position.x()), spawn_y.value_or(world.base_position.y()),
                           spawn_z.value_or(world.base_position.z())};
    world.base_yaw = spawn_yaw.value_or(world.base_yaw);
    const bool mock = mock_hardware || (!physics && sim::all_mock_hardware(model));
    if (mock && floating)
      throw CLI::ValidationError("--floating-base", "needs physics, and mock hardware has none: drop --floating-base, or "
                       "--mock-hardware (a description whose <ros2_control> blocks all name mock hardware runs mock "
                       "hardware; name gz_ros2_control/GazeboSimSystem there to simulate it)");
    const sim::BaseMount mount = floating ? sim::BaseMount::Floating : fixed ? sim::BaseMount::Fixed : sim::BaseMount::Auto;
    world.floating_base = !mock && sim::floating_base_for(model, mount);
    world.ground = !no_ground && (ground || world.floating_base);
    if (world.floating_base && mount == sim::BaseMount::Auto)
      spdlog::info("{}: the root link '{}' has no joint to `world`: a free base{}, as Gazebo spawns it (--fixed-base "
                   "welds it where it starts)",
                   model.urdf_path, model.root_link, world.ground ? " on the ground plane" : "");
    sim::Simulation sim(model, rates, start, world, mock ? sim::Backend::Mock : sim::Backend::Bullet);
    const bool brakes = !no_brakes && model.ros2_control_plugin.hold_joints;
    if (mock)
      spdlog::info("mock hardware ({}): no physics; the state follows the command as mock_components/GenericSystem",
                   mock_hardware ? "--mock-hardware" : "every <ros2_control> block names mock hardware");
    if (!mock) sim.actuators().set_brakes(brakes);
    if (!mock && !no_brakes && !brakes)
      spdlog::info("{}: <hold_joints>false</hold_joints>: joints nobody commands are not braked (effort and velocity "
                   "joints go limp, position PIDs hold on their gains), as --no-brakes",
                   model.urdf_path);
    for (const auto& n : sim.notes()) spdlog::info("{}", n);
    for (const auto& w : sim.warnings()) spdlog::warn("{}", w);
    for (const auto& line : sim.describe()) spdlog::info("{}", line);
    Bus bus(bus_flags.lcm_url, model.ns, bus_flags.hardware_lcm_url, hardware_reader_named(bus_flags.hardware_reader));
    bus.mirror_hardware(bus_flags.hardware_mirror_hz);
    sim::SimIo io(bus, sim, opt.lockstep, clock_every);
    io.set_max_command_age(std::max<int64_t>(1, std::llround(opt.watchdog_s * rates.control_hz)));
    sim::Stepper stepper(sim, io, opt);
    install_stop_signals(true);
    spdlog::info("ready ({}{}{}{}, {} actuators, {}control {:g} Hz, clock {:g} Hz, lcm {}{}{}, session {}{})",
                 opt.lockstep ? "lockstep" : "real time", mock ? ", mock hardware" : "",
                 opt.start_paused ? ", paused" : "",
                 world.floating_base ? (world.ground ? ", floating base on the ground" : ", floating base") :
                 (world.ground ? ", ground" : ""),
                 sim.hardware().size(), mock ? "" : fmt::format("physics {:g} Hz, ", rates.physics_hz),
                 rates.control_hz,
                 rates.control_hz / clock_every,
                 bus.url(), hardware_note(bus),
                 bus.ns().empty() ? "" : ", namespace " + bus.ns(), io.session(),
                 scheduling.empty() ? "" : ", " + scheduling);
    if (!stepper.run(stop_flag())) throw BusError("LCM stopped working (handle failed); is the multicast route still there?");
    const sim::Stepper::Summary run = stepper.summary();
    spdlog::info("stopped at step {} (sim time {:.3f} s); {} commands dropped{}{}; {:.1f}x real time, physics {:.3g} µs "
                 "a step", sim.step_count(), sim.time(), io.dropped(),
                 io.rejected_modes() ? fmt::format("; {} actuator commands in a mode not offered", io.rejected_modes())
                                     : "",
                 io.foreign_states() ? fmt::format("; {} hardware/state from another simulator", io.foreign_states())
                                     : "",
                 run.real_time_factor, run.physics_us);
    return int(kExitOk);
  });
}
