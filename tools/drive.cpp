// drive: teleop for a mobile base on the command line. Publishes a twist_t on
// `<controller>/cmd_vel` at a fixed rate of wall time, its linear.x and
// angular.z from muparser expressions in i (message count) and t (seconds), and
// a zero twist when it stops, so the robot does not coast until cmd_vel_timeout.
#include "tools/lib/clients/drive.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Drive a mobile base (teleop_twist_keyboard / rostopic pub -r on cmd_vel): publish twist_t on "
      "CONTROLLER/cmd_vel at --rate Hz, linear.x = LINEAR (m/s) and angular.z = ANGULAR (rad/s), expressions in i "
      "(message count) and t (seconds since start; functions of muparser and mod(a, b)); a zero twist at the end.\n"
      "Examples:\n"
      "  drive diff_drive_controller 0.2 0 --duration 5            # 1 m straight on\n"
      "  drive diff_drive_controller 0.1 '0.5*sin(t)'               # weave until Ctrl-C\n"
      "  drive diff_drive_controller 'mod(t,8.1416)<5 ? 0.2 : 0' 'mod(t,8.1416)<5 ? 0 : 0.5' --duration 32.57"
      "   # a 1 m square",
      "drive"};
  DriveFlags flags;
  add_drive_flags(app, flags);
  return run_program(app, argc, argv, [&] { return run_drive(flags); });
}
