// log2csv: converts an lcm-logger log file to one CSV per channel of our
// types (rosbag to CSV), with the same columns as state-logger, and says
// which channels it skipped and why.
#include "tools/lib/logs/log2csv.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Convert an lcm-logger log to CSV: one file per channel of lcm_control types (name: the channel with '/' as "
      "'__', e.g. j2_controller__command.csv), header = field paths (utime,position[0],...), numbers first, then "
      "strings (message, name[0],...; RFC 4180 quotes when a string holds a comma, quote, line break or edge space). "
      "Channels of other types are listed as skipped, with the reason.\n"
      "Examples:\n"
      "  lcm-logger --lcm-url=udpm://239.255.76.67:7667?ttl=0 run.lcmlog   # record (Ctrl-C to stop)\n"
      "  log2csv run.lcmlog --output-dir run_csv\n"
      "  log2csv run.lcmlog --channel 'joint_states|j2_controller/.*' --log-time\n"
      "  log2csv run.lcmlog -c joint_states --field position[j2] --field velocity[j2]",
      "log2csv"};
  Log2CsvFlags flags;
  add_log2csv_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_log2csv(flags); });
}
