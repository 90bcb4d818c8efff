// bus: rostopic and rosbag record/info for LCM, headless: list the channels on
// the bus with their types and rates, measure one channel's rate, print its
// messages, publish any lcm_control message from field=value pairs, record a
// log in lcm-logger's format, summarise a log, replay one.
#include "tools/lib/logs/bus_tool.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "The bus from a terminal (rostopic, rosbag info): list the channels with their types, rates and bandwidth, "
      "measure a channel's rate, print its messages, publish any lcm_control message, record, summarise and replay a "
      "log. Channel "
      "names may start with '/' as in ROS. A command that sees no message on its channel exits 4 and lists the "
      "channels it did see.\n"
      "Examples:\n"
      "  bus list                                      # what is on the bus (2 s)\n"
      "  bus netcheck --lcm-url 'udpm://239.255.76.67:7667?ttl=1'   # on two computers at once: can they hear each other?\n"
      "  bus hz hardware/state\n"
      "  bus hz hardware/state --namespace r0 --hardware-url auto   # a robot of `launch --robots`\n"
      "  bus echo joint_states --count 1\n"
      "  bus echo /joint_states/position --count 1     # one field (--field position[j2]: one joint's)\n"
      "  bus echo /j2_controller/command --csv --duration 5\n"
      "  bus pub j1_controller/command float64_t data=0.5\n"
      "  bus pub e_stop e_stop_t engaged=true source=me\n"
      "  bus pub arm_controller/command joint_trajectory_t joint_names=[j1,j2] \\\n"
      "      points[0].positions=[0.5,1.0] points[0].time_from_start=2\n"
      "  bus types joint_trajectory_t                  # the fields pub takes\n"
      "  bus record run.lcmlog -c 'joint_states|j2_controller/command'   # then Ctrl-C\n"
      "  bus info run.lcmlog\n"
      "  bus play run.lcmlog --speed 2 --loop          # replay it (Ctrl-C to stop)",
      "bus"};
  BusToolFlags flags;
  add_bus_tool_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_bus_tool(flags); });
}
