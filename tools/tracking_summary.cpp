// tracking-summary: how well joints followed their commands in an lcm-logger
// log: per joint, RMS and max of (command - position) over every joint_states
// message (command = the newest command with utime <= that message's utime),
// then wall time and real-time factor (which depend on the machine).
#include "tools/lib/logs/tracking_summary.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Tracking error per joint from an lcm-logger log: for every joint_states message, error = command - position, "
      "where command is the newest message on the joint's command channel with utime <= the joint_states utime "
      "(both on the sim clock; --time log joins by the logger's receive times instead, for commands stamped on "
      "another clock). Prints RMS and max |error| and the sample counts with fixed precision (identical for "
      "identical runs), then a line with the wall time and real-time factor (from the logger's receive times; these "
      "vary by machine).\n"
      "Example:\n"
      "  tracking-summary demo.lcmlog --joint j1=j1_controller/command --joint j2=j2_controller/command",
      "tracking-summary"};
  TrackingSummaryFlags flags;
  add_tracking_summary_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_tracking_summary(flags); });
}
