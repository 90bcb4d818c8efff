// tracking-summary: how closely joints followed their commands in a log (rms and max error per joint, joined by the messages' clock or the logger's).
// tools/tracking_summary.cpp parses the flags and calls run_tracking_summary.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct TrackingSummaryFlags {
  std::string log_path, js_channel = channels::kJointStates;
  std::vector<std::string> joints;  // JOINT=CHANNEL
  bool no_timing = false;
  std::string time_source = "utime";
};

void add_tracking_summary_flags(CLI::App& app, TrackingSummaryFlags& f);

int run_tracking_summary(TrackingSummaryFlags f);

}  // namespace lcm_control::tools
