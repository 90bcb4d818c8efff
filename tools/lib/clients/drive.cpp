#include "tools/lib/clients/drive.hpp"

#include <fmt/format.h>

#include <cmath>

#include "control/expression.hpp"
#include "lcm_control/twist_t.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/clients/time_base.hpp"

namespace lcm_control::tools {

void add_drive_flags(CLI::App& app, DriveFlags& f) {
  app.add_option("CONTROLLER", f.controller, "the diff_drive_controller's name (cmd_vel is CONTROLLER/cmd_vel)")
      ->required();
  app.add_option("LINEAR", f.linear, "forward speed, m/s: an expression in i and t")->required();
  app.add_option("ANGULAR", f.angular, "turn rate, rad/s (positive: left): an expression in i and t")->required();
  app.add_option("--rate", f.rate, "messages per second of wall time (above 1 / cmd_vel_timeout)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--duration", f.duration, "stop after S seconds (default: until Ctrl-C)")->check(CLI::PositiveNumber);
  app.add_option("--lateral", f.lateral,
                 "sideways speed, m/s (linear.y, positive: left), an expression in i and t: for a holonomic base "
                 "(mecanum_drive_controller, omni_wheel_drive_controller)");
  add_bus_flags(app, f.bus);
}

int run_drive(const DriveFlags& f) {
  Expressions exprs({f.linear, f.angular, f.lateral});
  install_stop_signals();
  Bus bus(f.bus.lcm_url, f.bus.ns, "", HardwareReader::Direct);
  // The channel the controller takes its twist on (cmd_vel; ROS 2's steering and mecanum drives: reference), when
  // the controller manager answers.
  const std::string channel =
      without_leading_slashes(f.controller) + "/" + twist_channel(bus, without_leading_slashes(f.controller), 0.5);
  check_command_channel(bus, channel, {twist_t::getTypeName(), 0}, 0.5);
  const CommandClock clock(bus, 0.3);
  fmt::print(stderr, "drive: twist_t on '{}' at {:g} Hz{} (Ctrl-C to stop)\n", bus.channel(channel), f.rate,
             f.duration > 0 ? fmt::format(" for {:g} s", f.duration) : "");
  twist_t msg{};
  const int64_t start = monotonic_us();
  const double period_us = 1e6 / f.rate;
  int64_t sent = 0;
  double values[3] = {0, 0, 0};
  for (int64_t i = 0; !stop_requested(); ++i) {
    const int64_t due = start + std::llround(double(i) * period_us);
    const double t = double(due - start) / 1e6;
    if (f.duration > 0 && t >= f.duration) break;
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
}

}  // namespace lcm_control::tools
