// cmctl: the controller_manager command line (list, list-types, load, unload,
// start, stop, switch, reload, and ROS 2's `ros2 control` verbs beside them)
// over controller_manager/request and /response, and the simulation's (pause,
// resume, step, reset, sim-status) over sim_server/request and /response. The verbs: tools/lib/cmctl_verbs.hpp.
#include "cli/cli.hpp"
#include "rt/stop_signal.hpp"
#include "tools/lib/clients/cmctl_verbs.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Talk to the controller manager (ROS's `rosrun controller_manager controller_manager ...`). Every request waits "
      "at most --timeout for the answer; a refused request prints the manager's reason and exits 1, no answer exits 4.\n"
      "Examples:\n"
      "  cmctl list\n"
      "  cmctl load j1_controller && cmctl start j1_controller\n"
      "  cmctl switch --start j2_effort_controller --stop j2_controller\n"
      "  cmctl --namespace robot1 list-types\n"
      "  cmctl set-controller-state arm_controller active      (ROS 2's words: ros2 control ...)\n"
      "  cmctl switch-controllers --activate vel --deactivate pos\n"
      "  cmctl list-hardware-interfaces\n"
      "  cmctl set-hardware-component-state Arm inactive\n"
      "  cmctl statistics\n"
      "  cmctl pause && cmctl step 100 && cmctl resume\n"
      "  cmctl reset -J j1=0.5",
      "cmctl"};
  BusFlags bus_flags;
  CmctlArgs args;
  add_bus_flags(app, bus_flags);
  app.add_option("--timeout", args.timeout, "seconds to wait for each answer")->check(CLI::PositiveNumber);
  app.fallthrough();  // `cmctl list --lcm-url URL` as well as `cmctl --lcm-url URL list`
  add_cmctl_verbs(app, args);
  return run_program(app, argc, argv, [&] {
    install_stop_signals();
    Bus bus(bus_flags.lcm_url, bus_flags.ns);  // LCM's receive thread: a short-lived tool waiting for answers
    return run_cmctl(app, args, bus);
  });
}
