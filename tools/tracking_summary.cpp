// tracking-summary: how well joints followed their commands in an lcm-logger
// log: per joint, RMS and max of (command - position) over every joint_states
// message (command = the newest command with utime <= that message's utime),
// then wall time and real-time factor (which depend on the machine).
#include <fmt/format.h>

#include <cmath>
#include <map>

#include "cli/cli.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/logs/log_file.hpp"
#include "tools/lib/clients/time_base.hpp"

namespace {

struct Pair {
  std::string joint, channel;
  std::vector<std::pair<int64_t, double>> commands;  // (time, value) in log order
  int64_t first_utime = 0;                           // of the first command, for the clock check
  double sum_sq = 0, max_abs = 0;
  int64_t samples = 0, before_first = 0;
};

}  // namespace

int main(int argc, char** argv) {
  using namespace lcm_control;
  CLI::App app{
      "Tracking error per joint from an lcm-logger log: for every joint_states message, error = command - position, "
      "where command is the newest message on the joint's command channel with utime <= the joint_states utime "
      "(both on the sim clock; --time log joins by the logger's receive times instead, for commands stamped on "
      "another clock). Prints RMS and max |error| and the sample counts with fixed precision (identical for "
      "identical runs), then a line with the wall time and real-time factor (from the logger's receive times; these "
      "vary by machine).\n"
      "Example:\n"
      "  tracking-summary demo.lcmlog --joint j1=j1_controller/command --joint j2=j2_controller/command",
      "tracking-summary"};
  std::string log_path, js_channel = channels::kJointStates;
  std::vector<std::string> joints;
  bool no_timing = false;
  std::string time_source = "utime";
  app.add_option("LOGFILE", log_path, "log written by lcm-logger")->required();
  app.add_option("--joint", joints, "JOINT=CHANNEL: a joint of joint_states and its command channel (float64_t)")
      ->required();
  app.add_option("--joint-states", js_channel, "channel of joint_state_t");
  app.add_flag("--no-timing", no_timing, "leave out the wall time / real-time factor line");
  app.add_option("--time", time_source, "join by utime (the messages' own clock, default) or log (receive time)")
      ->check(CLI::IsMember({"utime", "log"}));
  return lcm_control::run_program(app, argc, argv, [&]() -> int {
    std::vector<Pair> pairs;
    for (const auto& j : joints) {
      const auto eq = j.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == j.size())
        throw std::runtime_error(fmt::format("--joint '{}': expected JOINT=CHANNEL, e.g. j2=j2_controller/command", j));
      pairs.push_back({j.substr(0, eq), lcm_control::tools::without_leading_slashes(j.substr(eq + 1)), {}});
    }
    js_channel = lcm_control::tools::without_leading_slashes(js_channel);  // ROS's /joint_states too
    const auto log_file = lcm_control::tools::open_log(log_path);
    lcm::LogFile& log = *log_file;
    const bool by_log = time_source == "log";
    std::vector<joint_state_t> states;
    std::vector<int64_t> state_wall, state_time;
    joint_state_t js{};
    float64_t cmd{};
    for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent()) {
      if (ev->channel == js_channel) {
        if (!decode_guarded(js, ev->data, size_t(ev->datalen))) continue;
        states.push_back(js);
        state_wall.push_back(ev->timestamp);
        state_time.push_back(by_log ? ev->timestamp : js.utime);
        continue;
      }
      for (auto& p : pairs)
        if (ev->channel == p.channel && decode_guarded(cmd, ev->data, size_t(ev->datalen))) {
          if (p.commands.empty()) p.first_utime = cmd.utime;
          p.commands.emplace_back(by_log ? ev->timestamp : cmd.utime, cmd.data);
        }
    }
    if (states.empty()) throw ModelError(fmt::format("{}: no {} messages", log_path, js_channel));
    for (const auto& p : pairs) {
      if (p.commands.empty())
        throw ModelError(fmt::format("{}: no float64_t messages on {} (the command channel of {})", log_path,
                                     p.channel, p.joint));
      const std::string mixed = by_log ? "" : tools::mixed_clocks(js_channel, states.front().utime, p.channel,
                                                                  p.first_utime);
      if (!mixed.empty())
        throw ModelError(fmt::format(
            "{}: {}. Join by the logger's receive times with --time log, or publish the commands on the sim clock "
            "(turret-cmd and bus pub stamp sim time when sim_server's clock is on the bus; turret-cmd --sim-time "
            "ticks on it)",
            log_path, mixed));
    }
    for (auto& p : pairs) {
      std::stable_sort(p.commands.begin(), p.commands.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      int index = -1;
      for (size_t n = 0; n < states.size(); ++n) {
        const auto& s = states[n];
        for (int k = 0; k < s.num_joints; ++k)
          if (s.name[size_t(k)] == p.joint) index = k;
        if (index < 0 || index >= s.num_joints) continue;
        auto it = std::upper_bound(p.commands.begin(), p.commands.end(), state_time[n],
                                   [](int64_t t, const auto& c) { return t < c.first; });
        if (it == p.commands.begin()) {
          ++p.before_first;
          continue;
        }
        const double e = std::prev(it)->second - s.position[size_t(index)];
        p.sum_sq += e * e;
        p.max_abs = std::max(p.max_abs, std::fabs(e));
        ++p.samples;
      }
      if (index < 0) throw std::runtime_error(fmt::format("joint '{}' is not in {}", p.joint, js_channel));
      if (p.samples == 0)
        throw ModelError(fmt::format("{}: every {} message came before the first command on {}: nothing to compare",
                                     log_path, js_channel, p.channel));
    }
    const double sim_s = double(states.back().utime - states.front().utime) * 1e-6;
    fmt::print("tracking over {:.6f} s of sim time, {} joint_states messages:\n", sim_s, states.size());
    for (const auto& p : pairs)
      fmt::print("  {}: rms error {:.6f}, max error {:.6f} ({} samples, {} commands on {}, {} samples before the "
                 "first command)\n",
                 p.joint, p.samples ? std::sqrt(p.sum_sq / double(p.samples)) : 0.0, p.max_abs, p.samples,
                 p.commands.size(), p.channel, p.before_first);
    if (!no_timing) {
      const double wall_s = double(state_wall.back() - state_wall.front()) * 1e-6;
      fmt::print("timing (varies by machine): {:.3f} s of wall time, real-time factor {:.2f}\n", wall_s,
                 wall_s > 0 ? sim_s / wall_s : 0.0);
    }
    return int(kExitOk);
  });
}
