// tune: dynamic reconfigure for PID gains. Shows the gains in force for a
// joint, or sets some of them and confirms from the owner's answer.
#include "tools/lib/clients/tune.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Show or set the PID gains of a joint while it runs (dynamic reconfigure). The owner is sim_server for "
      "gazebo_ros_control/pid_gains, or a controller with its own PID (e.g. effort_controllers/"
      "JointPositionController). Gains not given keep their value; the new gains are confirmed from the owner's echo.\n"
      "Examples:\n"
      "  tune j2                          # print the gains in force\n"
      "  tune j2 --p 150 --d 50           # set p and d of sim_server's j2 PID\n"
      "  tune j2 --owner j2_controller --p 10 --i 1 --i-clamp 2",
      "tune"};
  TuneFlags flags;
  add_tune_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_tune(flags); });
}
