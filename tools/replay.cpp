// replay: re-drive a recorded run and say whether it does the same. Open loop (--controllers): the log's
// hardware/state messages drive a fresh controller manager in-process, one cycle each, as fast as the machine goes,
// with the recorded inputs handed over at their cycles; closed loop (--sim): the simulation re-runs with it. Its
// hardware/command and joint_states are compared with the recorded ones. Exit 0 identical (or within --tolerance),
// 1 diverged, 2 bad input.
#include "cli/cli.hpp"
#include "tools/lib/logs/replay.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Re-drive a recorded run (a log from bus record or lcm-logger, of sim_server or a real robot's hardware loop) "
      "and compare: open loop, the recorded hardware/state messages drive a fresh controller manager one cycle at a "
      "time with the recorded inputs (requests, commands, goals, gains) in their order, and its hardware/command and "
      "joint_states are compared with the recorded ones; closed loop (--sim), sim_server's simulation re-runs too, from "
      "its recorded command line and files, in lockstep with it. Exit 0 identical (or within --tolerance), 1 diverged (the "
      "first divergence named: channel, step, field, joint, both values), 2 bad input.\n"
      "Examples:\n"
      "  bus record run.lcmlog & launch config/turret_bot_demo.launch.yaml --duration 5\n"
      "  replay run.lcmlog --controllers                      # the configuration the run recorded in the log\n"
      "  replay run.lcmlog --controllers --config tuned.yaml  # what a change of gains changes\n"
      "  replay run.lcmlog --sim --config tuned.yaml          # ... with the simulation re-run (a lockstep log)\n"
      "  replay real_robot.lcmlog --controllers --urdf R.urdf --config C.yaml --tolerance 1e-6",
      "replay"};
  ReplayOptions o;
  bool controllers = false, sim = false;
  BusFlags bus_flags;
  std::vector<std::string> package_path, args, xacro_args;
  app.add_option("LOG", o.log, "the recorded run")->required();
  auto* open = app.add_flag("--controllers", controllers,
                            "open loop: re-drive the controller manager with the recorded hardware");
  auto* closed = app.add_flag("--sim", sim, "closed loop: re-run the simulation and the controller manager as recorded");
  open->excludes(closed);
  app.add_option("--urdf", o.urdf,
                 "the robot (.urdf or .xacro) instead of the one the run recorded (controller_manager/config)");
  add_config_flag(app, o.configs,
                  "controllers YAML instead of the recorded ones (repeatable, merged in order): to test a change");
  app.add_option("--namespace", bus_flags.ns, "the robot's namespace in the log (its channels are under it)");
  app.add_option("--tolerance", o.tolerance, "largest |recorded - replayed| taken as the same (default 0: bit for bit)")
      ->check(CLI::NonNegativeNumber);
  add_package_path_flag(app, package_path);
  add_arg_flag(app, args);
  add_xacro_arg_flag(app, xacro_args);
  return run_program(app, argc, argv, [&] {
    if (!controllers && !sim) throw CLI::ValidationError("--controllers or --sim", "say which loop to replay");
    try {
      o.load = load_options(package_path, bus_flags, args, xacro_args, {});
      const ReplayReport r = sim ? replay_closed_loop(o) : replay_controllers(o);
      std::fputs(replay_report_text(r, o.tolerance).c_str(), stdout);
      return r.within_tolerance() ? int(kExitOk) : int(kExitFailure);
    } catch (const ReplayInputError& e) {
      std::fprintf(stderr, "replay: error: %s\n", e.what());
      return int(kExitUsage);
    } catch (const ModelError& e) {
      for (const auto& p : e.problems()) std::fprintf(stderr, "replay: error: %s\n", p.c_str());
      return int(kExitUsage);
    }
  });
}
