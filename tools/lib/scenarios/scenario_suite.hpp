// `scenario run` and `scenario record`: scenario files (or folders of *.scenario.yaml) run one per CPU, each in a
// child process of its own on its own in-process bus, bounded in time; a table of results on stdout and, on
// request, JUnit XML for CI; and the golden log a scenario is later replayed against.
#pragma once

#include <string>
#include <vector>

#include "tools/lib/scenarios/scenario_run.hpp"

namespace lcm_control::tools {

struct SuiteOptions {
  std::vector<std::string> paths;  // scenario files, or folders searched for *.scenario.yaml
  int jobs = 0;                    // at once; 0: one per CPU this process may use
  std::string junit;               // "": none
  std::vector<std::string> package_path;
  double timeout_s = 600;  // wall time per scenario
  bool golden = true;
  bool verbose = false;
  int skipped_exit = 0;  // the exit code when every scenario was skipped (ctest's SKIP_RETURN_CODE: 77)  // every check in the table, with what it saw; else only those that failed
};

// The scenario files the paths name, each folder's *.scenario.yaml in name order; throws ModelError for a path that
// is neither.
std::vector<std::string> scenario_files(const std::vector<std::string>& paths);

// Runs them; returns 0 when every one passed (or was skipped), 1 when one failed, 2 when one could not run.
int run_scenarios(const SuiteOptions& o);

// Runs one scenario recording the whole bus to `log` (its golden log); 0 when its checks passed.
int record_scenario(const std::string& file, const std::string& log, const std::vector<std::string>& package_path);

// The table `scenario run` prints, and the JUnit XML it writes.
std::string results_table(const std::vector<ScenarioResult>& results, bool verbose = false);
std::string junit_xml(const std::vector<ScenarioResult>& results);

}  // namespace lcm_control::tools
