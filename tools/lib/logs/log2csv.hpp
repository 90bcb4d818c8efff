// log2csv: an LCM log turned into one CSV per channel of our types, every field a column.
// tools/log2csv.cpp parses the flags and calls run_log2csv.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct Log2CsvFlags {
  std::string log_path, output_dir = ".", channel_regex;
  std::vector<std::string> wanted;  // --field
  bool log_time = false;
};

void add_log2csv_flags(CLI::App& app, Log2CsvFlags& f);

int run_log2csv(const Log2CsvFlags& f);

}  // namespace lcm_control::tools
