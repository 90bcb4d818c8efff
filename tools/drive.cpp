// drive: teleop for a mobile base on the command line. Publishes a twist_t on
// `<controller>/cmd_vel` at a fixed rate of wall time, its linear.x and
// angular.z from muparser expressions in i (message count) and t (seconds), and
// a zero twist when it stops, so the robot does not coast until cmd_vel_timeout.
#include <fmt/format.h>

#include <cmath>

#include "cli/cli.hpp"
#include "control/expression.hpp"
#include "lcm_control/twist_t.hpp"
#include "tools/lib/command_check.hpp"
#include "tools/lib/support.hpp"
#include "tools/lib/time_base.hpp"

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
  std::string controller, linear, angular;
  double rate = 20, duration = 0;
  BusFlags bus_flags;
  app.add_option("CONTROLLER", controller, "the diff_drive_controller's name (cmd_vel is CONTROLLER/cmd_vel)")
      ->required();
  app.add_option("LINEAR", linear, "forward speed, m/s: an expression in i and t")->required();
  app.add_option("ANGULAR", angular, "turn rate, rad/s (positive: left): an expression in i and t")->required();
  app.add_option("--rate", rate, "messages per second of wall time (above 1 / cmd_vel_timeout)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--duration", duration, "stop after S seconds (default: until Ctrl-C)")->check(CLI::PositiveNumber);
  std::string lateral = "0";
  app.add_option("--lateral", lateral,
                 "sideways speed, m/s (linear.y, positive: left), an expression in i and t: for a holonomic base "
                 "(mecanum_drive_controller, omni_wheel_drive_controller)");
  add_bus_flags(app, bus_flags);
  return run_program(app, argc, argv, [&] {
    Expressions exprs({linear, angular, lateral});
    install_stop_signals();
    Bus bus(bus_flags.lcm_url, bus_flags.ns, "", HardwareReader::Direct);
    // The channel the controller takes its twist on (cmd_vel; ROS 2's steering and mecanum drives: reference), when
    // the controller manager answers.
    const std::string channel =
        without_leading_slashes(controller) + "/" + twist_channel(bus, without_leading_slashes(controller), 0.5);
    check_command_channel(bus, channel, {twist_t::getTypeName(), 0}, 0.5);
    const CommandClock clock(bus, 0.3);
    fmt::print(stderr, "drive: twist_t on '{}' at {:g} Hz{} (Ctrl-C to stop)\n", bus.channel(channel), rate,
               duration > 0 ? fmt::format(" for {:g} s", duration) : "");
    twist_t msg{};
    const int64_t start = monotonic_us();
    const double period_us = 1e6 / rate;
    int64_t sent = 0;
    double values[3] = {0, 0, 0};
    for (int64_t i = 0; !stop_requested(); ++i) {
      const int64_t due = start + std::llround(double(i) * period_us);
      const double t = double(due - start) / 1e6;
      if (duration > 0 && t >= duration) break;
      pump_until(bus, [] { return false; }, double(due - monotonic_us() - 1000) * 1e-6);  // sim time moves on
      sleep_until_us(due);
      if (stop_requested()) break;
      exprs.eval_checked(i, t, values);
      msg.utime = clock.now_us();
      msg.linear.x = values[0];
      msg.angular.z = values[1];
      msg.linear.y = values[2];
      bus.publish(channel, msg);
      ++sent;
    }
    msg = twist_t{};
    msg.utime = clock.now_us();
    bus.publish(channel, msg);
    fmt::print(stderr, "drive: sent {} twist{} and a stop on '{}'\n", sent, sent == 1 ? "" : "s", bus.channel(channel));
    return int(kExitOk);
  });
}
