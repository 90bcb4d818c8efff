// A scenario test as its YAML file gives it: a robot and its controllers (a launch file's keys, inline or `launch:
// FILE`), a timeline of inputs at sim times, and checks on what the run published. Read here (pure: no bus, no
// run); run headless in lockstep by scenario_run.hpp. The format: docs/scenarios.md.
#pragma once

#include <nlohmann/json.hpp>

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "tools/lib/launch/launch_plan.hpp"

namespace lcm_control::tools {

// One input: a message published on the robot's bus before the control cycle at time `at` of the scenario (sim
// time, but for what a pause holds and a reset sets back).
struct TimelineEntry {
  double at = 0;          // [s] of sim time
  std::string where;      // "file.yaml:12: command", for messages
  std::string channel;    // under the robot's namespace
  std::string type;       // as message_from_json takes it: "float64_t", "lcm_control.twist_t", ...
  std::string controller;  // the controller it is for ("" for none): checked against the run's
  nlohmann::json fields;  // utime left out: the cycle's sim time
};

// One check on the recorded run. `from`/`to` [s of sim time]: a window (every message in it), a time (from == to:
// the last message at or before it), or neither (< 0: the last message of the run).
struct Check {
  enum class Kind { Value, Tracking, Goal, Odometry };
  Kind kind = Kind::Value;
  std::string name;   // as the table and JUnit show it
  std::string where;  // "file.yaml:20"
  double from = -1, to = -1;
  // Value: `channel`'s `field` (a path or label: position[j2]) near `near` within `tolerance`, or within [min, max].
  std::string channel, field;
  std::optional<double> near, tolerance, min, max;
  // Tracking: joint_states' position of `joint` against the last value on `command` (`command_field`, or its first
  // number but utime): rms and largest error over the window.
  std::string joint, command_field;
  std::optional<double> rms_below, max_below;
  // Goal: the result (on `channel` = <controller>/result) of the last goal sent to the controller by time `to` is
  // `result` (SUCCEEDED, ...).
  std::string result, controller;
  // Odometry: <controller>/odom against sim_server/base_pose (ground truth), planar distance and heading.
  double within_m = 0, within_rad = 0;
};

struct Scenario {
  std::string file, name;  // name: the file's stem unless `name:` says
  LaunchPlan launch;       // lockstep always
  double duration = 0;     // [s] of sim time
  std::vector<std::string> requires_files;  // absent: skipped (a robot's files not in this checkout)
  std::vector<TimelineEntry> timeline;      // in time order (stable)
  std::vector<Check> checks;
  std::vector<std::string> package_path;  // `package_path:` (absolute): where $(find) and package:// look, first
  bool pauses_or_resets = false;  // the timeline pauses or resets the simulation
  std::string golden;  // a recorded golden log (scenario record) the run is replayed against; "" none
};

// Reads a scenario file; throws ModelError listing every problem (file:line: key: what to write instead).
Scenario read_scenario(const std::string& path, const std::vector<std::string>& package_path = {});

// A scenario's name from its file when the file does not say: "a/b.scenario.yaml" -> "b".
std::string scenario_name(const std::string& file);

// The keys a scenario file has beside a launch file's.
const std::set<std::string>& scenario_keys();

}  // namespace lcm_control::tools
