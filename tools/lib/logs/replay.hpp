// Open-loop replay (the front command's `replay --controllers`): a recorded run's hardware/state messages re-drive a
// fresh controller manager in-process, one cycle per recorded state (in the order they arrived), as fast as the
// machine goes; the recorded external inputs (controller_manager requests, controllers' commands and goals, gains,
// e-stops) are handed to it before the cycle the live manager took each in at (its stamps, cm_inputs_t; a log
// without them: in the log's order), and what it commands (hardware/command) and publishes (joint_states, each
// controller's own channels) is compared with what was recorded. A lockstep recording with unchanged code and
// configuration replays bit for bit. Closed loop (replay_closed_loop): the simulation re-runs too, from sim_server's
// recorded configuration, with its recorded wrenches.
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control::tools {

// The log or the configuration cannot be replayed (a bad, truncated or foreign log; a robot that is not the log's):
// one line naming the file, the event or the joint, and what to pass.
class ReplayInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ReplayOptions {
  std::string log;                   // an LCM log (bus record or lcm-logger)
  // The robot and its controllers; "" and none: the configuration the run recorded in the log (run_config_t); a
  // --config given with the recorded robot replaces the recorded files (to test a change).
  std::string urdf;
  std::vector<std::string> configs;
  LoadOptions load;                  // package path, xacro arguments, namespace (the log's channels are under it)
  double tolerance = 0;              // |recorded - replayed| allowed per value; 0: bit for bit
};

// What differs first: the channel, the step (hardware/command) or message time, the field and its index (an actuator
// or joint name), and both values.
struct Divergence {
  std::string channel;
  int64_t step = -1, utime = 0;
  std::string field, index;
  double recorded = 0, replayed = 0;
};

struct ChannelSummary {
  std::string channel;
  int64_t compared = 0;  // messages compared
  int64_t differing = 0;  // of those, with a value beyond the tolerance
  double max_abs = 0;     // the largest |recorded - replayed| over every value compared
};

struct ReplayReport {
  int64_t events = 0, states = 0, fed = 0;  // log events read; hardware states replayed; inputs handed over
  std::vector<std::string> notes;           // where the configuration came from
  std::vector<ChannelSummary> channels;
  std::optional<Divergence> first;
  double replay_s = 0;  // the re-driving itself, from the configuration loaded to the comparison done (wall time)
  bool within_tolerance() const { return !first.has_value(); }
};

// Throws ReplayInputError (or ModelError for the configuration) when the replay cannot be made.
ReplayReport replay_controllers(const ReplayOptions& options);

// Closed loop (`--sim`): sim_server's simulation and a controller manager, both in this process and built from the
// configurations the run recorded, stepped in lockstep with the recorded inputs fed at their cycles (sim_server's
// wrenches at the step their answers name; a log with a pause, step or reset is refused); the joint_states and
// hardware/command they make are compared with the log's.
ReplayReport replay_closed_loop(const ReplayOptions& options);

// "identical: ..." or "diverged: first at ...", then a line per channel.
std::string replay_report_text(const ReplayReport& report, double tolerance);

}  // namespace lcm_control::tools
