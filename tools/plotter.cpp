// plotter: rqt_plot to a file. Plots field paths such as
// `joint_states.velocity[1]` against time, from an lcm-logger log or live from
// the bus for a while, to PNG or SVG through gnuplot.
#include "tools/lib/logs/plotter.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Plot message fields against time (rqt_plot) to PNG or SVG with gnuplot, from an lcm-logger log (--log) or "
      "live from the bus (--duration), or as text in the terminal (--terminal). PATH is CHANNEL.FIELD with the field "
      "paths of state-logger / log2csv numeric columns (text columns such as message cannot be plotted) or the "
      "dashboard's labels (joint_states.position[j2]); "
      "ROS-style /CHANNEL/FIELD works too, and a bare channel of a one-value message (float64_t) plots its data. "
      "Time on x is seconds from the first message (receive time, or the messages' utime with --time utime).\n"
      "Examples:\n"
      "  plotter j2_controller/command.data joint_states.velocity[1] --log run.lcmlog --output run.png\n"
      "  plotter /j2_controller/command /joint_states/velocity[1] --duration 10 --output live.svg\n"
      "  plotter joint_states.position[j2] --duration 5 --terminal   # text plot in the terminal, no file\n"
      "  plotter --xy diff_drive_controller/odom.position.x diff_drive_controller/odom.position.y \\\n"
      "      sim_server/base_pose.position.x sim_server/base_pose.position.y --log run.lcmlog -o path.png\n"
      "  plotter joint_states.velocity[1] --duration 60 --live --output run.png # live text view, PNG at the end",
      "plotter"};
  PlotterFlags flags;
  add_plotter_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_plotter(flags); });
}
