#include "sim_server/program.hpp"

#include <algorithm>
#include <cmath>

#include "bus/run_config.hpp"
#include "description/initial_positions.hpp"
#include "description/load.hpp"
#include "rt/clock.hpp"
#include "rt/log.hpp"
#include "rt/stop_signal.hpp"
#include "sim_server/mock_hardware.hpp"
#include "sim_server/sim_io.hpp"

namespace lcm_control::sim {

void add_program_flags(CLI::App& app, ProgramFlags& f) {
  add_robot_process_flags(app, f.robot, "URDF (or .urdf.xacro, with --xacro-arg) with <transmission> tags",
                          "ros_control YAML (gazebo_ros_control/pid_gains); none: every joint direct");
  app.add_option("--mode", f.mode,
                 "realtime: paced by the wall clock; lockstep: step only when the controller manager answers "
                 "(deterministic, as fast as the two processes go)")
      ->check(CLI::IsMember({"realtime", "lockstep"}))
      ->capture_default_str();
  app.add_option("--physics-rate", f.physics_hz,
                 "physics steps per second (default 1000, or the nearest multiple of a YAML's update_rate at or above "
                 "1000)");
  app.add_option("--control-rate", f.control_hz,
                 "hardware state/command exchanges per second, dividing --physics-rate (default: the YAML's "
                 "controller_manager update_rate, else 1000)");
  app.add_option("--clock-rate", f.clock_hz,
                 "sim_clock_t on `clock` this often, in Hz of sim time (nearest whole number of control steps); 0: "
                 "every control step")
      ->capture_default_str();
  StepperOptions& opt = f.stepper;
  app.add_option("--duration", opt.duration_s, "stop after this many seconds of sim time (0: run until stopped)");
  app.add_option("--lockstep-timeout", opt.lockstep_timeout_s,
                 "lockstep: republish the state this often (s) while no command comes")
      ->capture_default_str();
  app.add_option("--watchdog", opt.watchdog_s, "real time: hold every actuator after this long (s) without a command")
      ->capture_default_str();
  app.add_option("--overrun", f.overrun,
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
  app.add_option("--timer-slack-ns", f.timer_slack_ns,
                 "real time: how late the pacing timer may wake (Linux's default for a normal thread: 50000)")
      ->check(CLI::Range(1L, 10000000L))
      ->capture_default_str();
  app.add_option("-J,--initial-position", f.initial,
                 "JOINT=VALUE: start that joint there (rad or m; repeatable), as spawn_model's -J; joints not given "
                 "start at 0, and a start outside the URDF limits is clamped into them")
      ->check(initial_position_problem);
  app.add_flag("--paused", opt.start_paused,
               "start paused, as Gazebo's paused:=true: the state is published and controllers can be spawned, but "
               "nothing steps until `cmctl resume` (or `cmctl step N`)");
  auto* floating_flag = app.add_flag(
      "--floating-base", f.floating,
      "the root link is free, even if the URDF names it `world`; its ground truth goes on sim_server/base_pose "
      "(default: free when the URDF has no joint to `world`, as Gazebo spawns it, welded when it has)");
  app.add_flag("--fixed-base", f.fixed,
               "weld the root link to the world where it starts, even when the URDF has no joint to `world` (an arm "
               "bolted to a table)")
      ->excludes(floating_flag);
  app.add_flag("--ground", f.ground, "a ground plane at z = 0 (default with a free base)");
  app.add_flag("--no-ground", f.no_ground, "no ground plane, even with a free base")->excludes("--ground");
  app.add_option("--base-pose", f.base_pose,
                 "X Y Z YAW: where the root link starts (m, rad; default 0 0 0 0); a free base below the ground is "
                 "lifted onto it")
      ->expected(4);
  app.add_option("-x", f.x, "the root link's start x (m), as ros_gz_sim create and spawn_model take it")
      ->excludes("--base-pose");
  app.add_option("-y", f.y, "its start y (m)")->excludes("--base-pose");
  app.add_option("-z", f.z, "its start z (m)")->excludes("--base-pose");
  app.add_option("-Y", f.yaw, "its start yaw (rad)")->excludes("--base-pose");
  app.add_flag("--no-brakes", f.no_brakes,
               "joints nobody commands, or held by the watchdog, are left to their PID (position) or limp (effort, "
               "velocity), as in Gazebo (default: braked where they are)");
  auto* mock_flag = app.add_flag(
      "--mock-hardware", f.mock_hardware,
      "play the robot without physics, as ros2_control's mock_components/GenericSystem: the state follows "
      "the command (the default when every <ros2_control> block names mock_components/GenericSystem)");
  app.add_flag("--physics", f.physics,
               "simulate the robot in Bullet even when its <ros2_control> blocks name mock hardware (a description "
               "written for mock_components or a demo's mock-like plugin, run as gz_ros2_control would run it)")
      ->excludes(mock_flag);
}

namespace {
SimulationRates given_rates(const ProgramFlags& f) {
  SimulationRates r;
  r.physics_hz = f.physics_hz.value_or(r.physics_hz);
  r.control_hz = f.control_hz.value_or(r.control_hz);
  return r;
}
}  // namespace

RunPlan plan_run(const ProgramFlags& f, const RobotModel& model) {
  RunPlan p;
  p.rates = given_rates(f);
  substeps_for(p.rates);
  // A ROS 2 parameter file's update_rate is the control rate (gz_ros2_control runs the manager at it) unless
  // --control-rate says otherwise; the physics rate becomes its nearest multiple at or above 1 kHz if not given.
  if (model.update_rate_hz && !f.control_hz) {
    p.rates.control_hz = *model.update_rate_hz;
    if (!f.physics_hz) p.rates.physics_hz = p.rates.control_hz * std::ceil(1000.0 / p.rates.control_hz - 1e-9);
    substeps_for(p.rates);
    p.notes.push_back(fmt::format("{}: control rate {:g} Hz from controller_manager's update_rate (physics {:g} Hz)",
                                  model.config_path, p.rates.control_hz, p.rates.physics_hz));
  }
  p.clock_every = clock_every_for(p.rates.control_hz, f.clock_hz);
  p.start = model.initial_positions;
  for (const auto& a : f.initial) {
    const auto [joint, q] = parse_initial_position(a);
    p.start[joint] = q;
  }
  if (f.base_pose.size() == 4) {
    p.world.base_position = {f.base_pose[0], f.base_pose[1], f.base_pose[2]};
    p.world.base_yaw = f.base_pose[3];
  }
  p.world.base_position = {f.x.value_or(p.world.base_position.x()), f.y.value_or(p.world.base_position.y()),
                           f.z.value_or(p.world.base_position.z())};
  p.world.base_yaw = f.yaw.value_or(p.world.base_yaw);
  p.mock = f.mock_hardware || (!f.physics && all_mock_hardware(model));
  if (p.mock && f.floating)
    throw CLI::ValidationError("--floating-base",
                               "needs physics, and mock hardware has none: drop --floating-base, or --mock-hardware (a "
                               "description whose <ros2_control> blocks all name mock hardware runs mock hardware; "
                               "name gz_ros2_control/GazeboSimSystem there to simulate it)");
  const BaseMount mount = f.floating ? BaseMount::Floating : f.fixed ? BaseMount::Fixed : BaseMount::Auto;
  p.world.floating_base = !p.mock && floating_base_for(model, mount);
  p.world.ground = !f.no_ground && (f.ground || p.world.floating_base);
  if (p.world.floating_base && mount == BaseMount::Auto)
    p.notes.push_back(fmt::format("{}: the root link '{}' has no joint to `world`: a free base{}, as Gazebo spawns it "
                                  "(--fixed-base welds it where it starts)",
                                  model.urdf_path, model.root_link, p.world.ground ? " on the ground plane" : ""));
  p.brakes = !p.mock && !f.no_brakes && model.ros2_control_plugin.hold_joints;
  if (p.mock)
    p.notes.push_back(fmt::format("mock hardware ({}): no physics; the state follows the command as "
                                  "mock_components/GenericSystem",
                                  f.mock_hardware ? "--mock-hardware" : "every <ros2_control> block names mock hardware"));
  if (!p.mock && !f.no_brakes && !p.brakes)
    p.notes.push_back(fmt::format("{}: <hold_joints>false</hold_joints>: joints nobody commands are not braked (effort "
                                  "and velocity joints go limp, position PIDs hold on their gains), as --no-brakes",
                                  model.urdf_path));
  return p;
}

int run_sim_server(ProgramFlags f) {
  StepperOptions& opt = f.stepper;
  opt.lockstep = f.mode == "lockstep";
  opt.overrun = f.overrun == "skip" ? Overrun::Skip : Overrun::CatchUp;
  substeps_for(given_rates(f));  // bad rates fail before anything else is said
  std::string scheduling = apply_scheduling(f.robot.sched);
  if (!opt.lockstep) set_timer_slack(f.timer_slack_ns);
  if (!opt.lockstep && opt.spin_us > 0)
    scheduling += fmt::format("{}spinning {} us before each deadline", scheduling.empty() ? "" : ", ", opt.spin_us);
  setup_logging("sim_server", f.robot.log_level);
  LoadOptions options = load_options(f.robot.files, f.robot.bus);
  options.config_from_plugin = true;
  const RobotModel model = load_robot_model(f.robot.files.urdf, f.robot.files.config, options);
  for (const auto& n : model.notes) spdlog::info("{}", n);
  for (const auto& w : model.warnings) spdlog::warn("{}", w);
  const RunPlan plan = plan_run(f, model);
  for (const auto& n : plan.notes) spdlog::info("{}", n);
  Simulation sim(model, plan.rates, plan.start, plan.world, plan.mock ? Backend::Mock : Backend::Bullet);
  if (!plan.mock) sim.actuators().set_brakes(plan.brakes);
  for (const auto& n : sim.notes()) spdlog::info("{}", n);
  for (const auto& w : sim.warnings()) spdlog::warn("{}", w);
  for (const auto& line : sim.describe()) spdlog::info("{}", line);
  const BusFlags& b = f.robot.bus;
  Bus bus(b.lcm_url, model.ns, b.hardware_lcm_url, hardware_reader_named(b.hardware_reader));
  bus.mirror_hardware(b.hardware_mirror_hz);
  SimIo io(bus, sim, opt.lockstep, plan.clock_every);
  io.set_max_command_age(std::max<int64_t>(1, std::llround(opt.watchdog_s * plan.rates.control_hz)));
  Stepper stepper(sim, io, opt);
  // What it was started with, on sim_server/config now and on a CONFIG request, so that a recording replays alone.
  run_config_t config;
  const std::string unreadable = read_run_config(model, "sim_server", command_line(), &config);
  auto publish_config = [&]() -> std::pair<bool, std::string> {
    if (!unreadable.empty()) return {false, "cannot publish the run's configuration: " + unreadable};
    config.utime = wall_us();
    bus.lcm().publish(bus.channel(channels::kSimConfig), &config);
    return {true, fmt::format("published the run's configuration on {} ({}, {} file(s), {} bytes)",
                              bus.channel(channels::kSimConfig), model.urdf_path, config.num_configs,
                              config.getEncodedSize())};
  };
  stepper.set_config_publisher(publish_config);
  publish_config();
  install_stop_signals(true);
  const WorldOptions& world = plan.world;
  spdlog::info("ready ({}{}{}{}, {} actuators, {}control {:g} Hz, clock {:g} Hz, lcm {}{}{}, session {}{})",
               opt.lockstep ? "lockstep" : "real time", plan.mock ? ", mock hardware" : "",
               opt.start_paused ? ", paused" : "",
               world.floating_base ? (world.ground ? ", floating base on the ground" : ", floating base")
                                   : (world.ground ? ", ground" : ""),
               sim.hardware().size(), plan.mock ? "" : fmt::format("physics {:g} Hz, ", plan.rates.physics_hz),
               plan.rates.control_hz, plan.rates.control_hz / plan.clock_every, bus.url(), hardware_note(bus),
               bus.ns().empty() ? "" : ", namespace " + bus.ns(), io.session(), scheduling.empty() ? "" : ", " + scheduling);
  if (!stepper.run(stop_flag()))
    throw BusError("LCM stopped working (handle failed); is the multicast route still there?");
  const Stepper::Summary run = stepper.summary();
  spdlog::info("stopped at step {} (sim time {:.3f} s); {} commands dropped{}{}; {:.1f}x real time, physics {:.3g} µs "
               "a step",
               sim.step_count(), sim.time(), io.dropped(),
               io.rejected_modes() ? fmt::format("; {} actuator commands in a mode not offered", io.rejected_modes()) : "",
               io.foreign_states() ? fmt::format("; {} hardware/state from another simulator", io.foreign_states()) : "",
               run.real_time_factor, run.physics_us);
  return kExitOk;
}

}  // namespace lcm_control::sim
