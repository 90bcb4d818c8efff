// One scenario run headless in lockstep, in this process: sim_server's simulation and a controller manager built
// from the scenario's launch (the command lines launch would start them with) on an in-process bus (ClosedLoop), the
// controllers spawned as launch spawns them, the timeline's inputs published before their cycles, everything the
// bus carries recorded (to an LCM log on request: `scenario record`'s golden log, which `replay --sim` reads), then
// the checks read what was recorded. Identical files give identical results, bit for bit.
#pragma once

#include <string>
#include <vector>

namespace lcm_control::tools {

struct CheckResult {
  std::string name, where;
  bool passed = false;
  std::string detail;  // the values it saw: "position[j1] = 0.4991 at t=3.000 s, wanted 0.5 ± 0.01"
};

struct ScenarioResult {
  enum class Outcome { Passed, Failed, Skipped, Error };
  Outcome outcome = Outcome::Error;
  std::string name, file;
  std::string why;  // Error: why it could not run (every problem, one a line); Skipped: the file it needs
  std::vector<CheckResult> checks;
  double sim_s = 0, wall_s = 0;
  int64_t steps = 0, messages = 0;
};

const char* outcome_name(ScenarioResult::Outcome o);  // "passed", "FAILED", "skipped", "ERROR"

struct ScenarioRunOptions {
  std::vector<std::string> package_path;
  std::string record_log;  // "": none; else the whole bus as an LCM log, sim time as each event's timestamp
  bool golden = true;      // replay the scenario's golden log (if it names one) with today's files
};

// Never throws: what goes wrong is the result's Error with why.
ScenarioResult run_scenario(const std::string& file, const ScenarioRunOptions& options = {});

}  // namespace lcm_control::tools
