// state-logger: channels of the bus written as CSV while they arrive (one file, stdout, or one per channel), every field a column.
// tools/state_logger.cpp parses the flags and calls run_state_logger.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct StateLoggerFlags {
  std::vector<std::string> channel_names;
  std::string output, output_dir;
  double duration = 0;
  int64_t count = 0;
  BusFlags bus;
};

void add_state_logger_flags(CLI::App& app, StateLoggerFlags& f);

int run_state_logger(StateLoggerFlags f);

}  // namespace lcm_control::tools
