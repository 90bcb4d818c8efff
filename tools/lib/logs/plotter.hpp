// plotter: fields of messages (a log's, or the bus's for a while) plotted with gnuplot to an image, a data file or the terminal, against time or one another.
// tools/plotter.cpp parses the flags and calls run_plotter.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"

namespace lcm_control::tools {

struct PlotterFlags {
  std::vector<std::string> paths;  // CHANNEL.FIELD
  std::string log_path, output, data_file, title, time_source = "receive";
  double duration = 0;
  int width = 1000, height = 600;
  bool terminal = false, live = false, xy = false;
  BusFlags bus;
};

void add_plotter_flags(CLI::App& app, PlotterFlags& f);

int run_plotter(PlotterFlags f);

}  // namespace lcm_control::tools
