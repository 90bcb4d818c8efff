// bus: rostopic and rosbag for LCM, headless: the channels on the bus, a channel's rate and messages, any message published from field=value pairs, a log recorded, summarised and played.
// tools/bus.cpp parses the flags and calls run_bus_tool.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct BusToolFlags {
  BusFlags bus;
  std::string channel, type, log_path, record_regex = ".*";
  std::vector<std::string> fields, assignments;
  double list_duration = 2, duration = 0, rate = 0, net_duration = 3, speed = 1;
  int64_t count = 0;
  size_t window = 1000;
  bool csv = false, answer_only = false, force = false, loop = false;
  CLI::App *list = nullptr, *hz = nullptr, *echo = nullptr, *pub = nullptr, *types = nullptr, *netcheck = nullptr,
           *record = nullptr, *play = nullptr, *info = nullptr;  // the subcommands
};

void add_bus_tool_flags(CLI::App& app, BusToolFlags& f);

int run_bus_tool(BusToolFlags f);

}  // namespace lcm_control::tools
