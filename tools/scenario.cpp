// scenario: regression tests of a robot and its controllers, headless in lockstep at many times real time. `run`
// runs scenario files (or folders of *.scenario.yaml) one per CPU and prints a table (JUnit XML with --junit);
// `record` keeps a scenario's golden log, which later runs replay. Exit 0 all passed, 1 a check failed, 2 a
// scenario could not run.
#include "cli/cli.hpp"
#include "rt/log.hpp"
#include "tools/lib/scenarios/scenario_suite.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Scenario tests: a robot and its controllers (a launch file's keys), a timeline of inputs at sim times "
      "(commands, trajectory goals, cmd_vel, switches, e-stops, wrenches, any message) and checks on what the run "
      "published (a field at a time or over a window, tracking, a goal's result, odometry against ground truth), run "
      "headless in lockstep in one process per scenario, as fast as the machine goes. The format: docs/scenarios.md.\n"
      "Examples:\n"
      "  scenario run test/scenarios                 # every *.scenario.yaml under it, one per CPU\n"
      "  scenario run a.scenario.yaml --junit out.xml\n"
      "  scenario record a.scenario.yaml a.golden.lcmlog   # then `golden: a.golden.lcmlog` in the file",
      "scenario"};
  app.require_subcommand(1);
  SuiteOptions o;
  std::string file, log;
  CLI::App* run = app.add_subcommand("run", "run scenarios and print a table of results");
  run->add_option("PATHS", o.paths, "scenario files, or folders searched for *.scenario.yaml")->required();
  run->add_option("-j,--jobs", o.jobs, "scenarios at once (default: one per CPU)")->check(CLI::NonNegativeNumber);
  run->add_option("--junit", o.junit, "also write the results as JUnit XML to this file");
  run->add_option("--timeout", o.timeout_s, "wall seconds a scenario may take before it is stopped (default 600)")
      ->check(CLI::PositiveNumber);
  run->add_flag("!--no-golden", o.golden, "do not replay the scenarios' golden logs");
  run->add_option("--skipped-exit", o.skipped_exit, "exit code when every scenario was skipped (default 0; ctest: 77)");
  run->add_flag("-v,--verbose", o.verbose, "every check with what it saw, not only those that failed");
  CLI::App* record = app.add_subcommand("record", "run one scenario and keep its whole bus as its golden log");
  record->add_option("FILE", file, "the scenario")->required()->check(CLI::ExistingFile);
  record->add_option("LOG", log, "the golden log to write")->required();
  std::string log_level = "warn";
  for (CLI::App* sub : {run, record}) {
    add_package_path_flag(*sub, o.package_path);
    sub->add_option("--log-level", log_level, "the controller manager's and simulation's log lines shown (default warn)");
  }
  return run_program(app, argc, argv, [&] {
    setup_logging("scenario", log_level);
    if (*record) return record_scenario(file, log, o.package_path);
    return run_scenarios(o);
  });
}
