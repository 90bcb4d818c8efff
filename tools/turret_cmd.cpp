// turret-cmd: rqt's Message Publisher on the command line. Publishes muparser
// expressions in i (message count) and t (seconds since start) to a controller's
// command channel, once or at a fixed rate of wall time; on sim time it has the
// controller manager generate them (a command source), or for a raw channel
// paces itself by hardware/state (one per control step).
#include "tools/lib/clients/turret_cmd.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Publish commands to a controller (rqt Message Publisher). EXPR is a muparser expression in i (message count "
      "from 0) and t (seconds since start); one EXPR sends lcm_control.float64_t, several send float64_array_t (group "
      "controllers). TARGET is a controller name (channel TARGET/command) or, if it contains '/' or with --as-channel, a "
      "channel name.\n"
      "Examples:\n"
      "  turret-cmd j1_controller 0.5                                   # once\n"
      "  turret-cmd j2_controller '3.14*sin(i/100)' --rate 60           # until Ctrl-C\n"
      "  turret-cmd /j2_controller/command '3.14*sin(2*pi*0.5*t)' --rate 100 --duration 10\n"
      "  turret-cmd arm_controller 0.1 '-0.2*t' --rate 50 --count 100   # float64_array_t\n"
      "  turret-cmd j2_controller 'i<500 ? 0 : 1' --sim-time            # every control step, exact\n"
      "  turret-cmd j2_controller '3.14*sin(i/100)' --sim-time --rate 60 --duration 20\n"
      "With --sim-time and a controller TARGET, the controller manager generates the commands itself (a command "
      "source): message i is due at sim time i/rate after the first control step it sees, is delivered before that "
      "step's update and published on TARGET/command, so every step gets its own command and lockstep runs repeat "
      "exactly; while it runs, other messages on TARGET/command are ignored (counted in its end). turret-cmd waits for the source to end (--count, --duration) or for Ctrl-C, which removes it. With "
      "--sim-time and a channel TARGET, turret-cmd paces itself by hardware/state (every control step): best effort, a message can "
      "reach the controller a step late.",
      "turret-cmd"};
  TurretCmdFlags flags;
  add_turret_cmd_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_turret_cmd(flags); });
}
