// state-logger: `rostopic echo -p` for LCM. Writes every message of the given
// channels (default joint_states) as CSV rows whose header is the field paths.
#include "tools/lib/clients/state_logger.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Write messages of LCM channels as CSV (rostopic echo -p). The header is the field paths of the message "
      "(utime,position[0],...,velocity[0],...), numbers first, then strings (name[0],...; RFC 4180 quotes when a "
      "string holds a comma, quote, line break or edge space); array lengths are left out. One channel goes to "
      "stdout or --output; several channels go to one file per channel in --output-dir (joint_states.csv, "
      "j2_controller__command.csv), the same names and columns as log2csv. Rows are flushed every 0.2 s and on exit.\n"
      "Examples:\n"
      "  state-logger --output joint_states.csv               # joint_states until Ctrl-C\n"
      "  state-logger joint_states j2_controller/command --output-dir run1 --duration 10\n"
      "  state-logger j2_controller/state --count 100",
      "state-logger"};
  StateLoggerFlags flags;
  add_state_logger_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_state_logger(flags); });
}
