// dashboard: the robot in a browser. Serves a page (the robot in 3D from its URDF, live plots of any field,
// sliders and expressions for command channels, PID gains, the controllers and their switches, e-stop, loop
// statistics) and streams the bus to it over a WebSocket, each channel's newest message at the display rate.
#include <CLI/CLI.hpp>

#include "cli/cli.hpp"
#include "dashboard/app.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app(
      "Serve the robot's dashboard to a browser: the robot in 3D, live plots of any field, sliders and expressions "
      "for command channels, PID gains, controllers (load, start, stop, switch), e-stop and loop statistics.\n"
      "  dashboard --urdf config/turret_bot.urdf           # then open http://127.0.0.1:8080/\n"
      "  dashboard --namespace r1 --port 8081 --read-only",
      "dashboard");
  dashboard::Options o;
  add_bus_flags(app, o.bus);
  add_package_path_flag(app, o.package_path);
  app.add_option("--urdf", o.urdf,
                 "the robot's URDF or .urdf.xacro (with --xacro-arg), for the 3D view (meshes from package:// or "
                 "beside it)");
  add_xacro_arg_flag(app, o.xacro_args);
  app.add_option("--port", o.port, "TCP port of the page (0: one the system picks; the URL is printed)")
      ->check(CLI::Range(0, 65535));
  app.add_option("--bind", o.bind,
                 "address to serve on (default 127.0.0.1: this computer only; there is no authentication)");
  app.add_option("--rate", o.rate_hz, "messages per second per channel at most (latest wins)")
      ->check(CLI::Range(1.0, 1000.0));
  app.add_flag("--read-only", o.read_only, "show the robot, refuse every command from the page");
  app.add_option("--web-root", o.web_root, "folder of the built page (default: share/lcm_control/dashboard of "
                                           "the build tree or of the installation)");
  app.add_option("--nice", o.nice,
                 "run at this nice value (0 to 19; default 10), so that a busy page never takes the CPU of the loop "
                 "it shows")
      ->check(CLI::Range(0, 19));
  app.add_option("--timeout", o.timeout_s, "seconds to wait for the controller manager's answers")
      ->check(CLI::PositiveNumber);
  app.add_option("--duration", o.duration_s, "stop after S seconds (default: until Ctrl-C)")
      ->check(CLI::PositiveNumber);
  return run_program(app, argc, argv, [&] { return dashboard::run(o); });
}
