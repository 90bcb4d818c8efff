#include "tools/lib/logs/tracking_summary.hpp"

#include <fmt/format.h>

#include <cmath>
#include <map>

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

namespace lcm_control::tools {

void add_tracking_summary_flags(CLI::App& app, TrackingSummaryFlags& f) {
  app.add_option("LOGFILE", f.log_path, "log written by lcm-logger")->required();
  app.add_option("--joint", f.joints, "JOINT=CHANNEL: a joint of joint_states and its command channel (float64_t)")
      ->required();
  app.add_option("--joint-states", f.js_channel, "channel of joint_state_t");
  app.add_flag("--no-timing", f.no_timing, "leave out the wall time / real-time factor line");
  app.add_option("--time", f.time_source, "join by utime (the messages' own clock, default) or log (receive time)")
      ->check(CLI::IsMember({"utime", "log"}));
}

int run_tracking_summary(TrackingSummaryFlags f) {
  std::vector<Pair> pairs;
  for (const auto& j : f.joints) {
    const auto eq = j.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == j.size())
      throw std::runtime_error(fmt::format("--joint '{}': expected JOINT=CHANNEL, e.g. j2=j2_controller/command", j));
    pairs.push_back({j.substr(0, eq), lcm_control::tools::without_leading_slashes(j.substr(eq + 1)), {}});
  }
  f.js_channel = lcm_control::tools::without_leading_slashes(f.js_channel);  // ROS's /joint_states too
  const auto log_file = lcm_control::tools::open_log(f.log_path);
  lcm::LogFile& log = *log_file;
  const bool by_log = f.time_source == "log";
  std::vector<joint_state_t> states;
  std::vector<int64_t> state_wall, state_time;
  joint_state_t js{};
  float64_t cmd{};
  for (const lcm::LogEvent* ev = log.readNextEvent(); ev; ev = log.readNextEvent()) {
    if (ev->channel == f.js_channel) {
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
  if (states.empty()) throw ModelError(fmt::format("{}: no {} messages", f.log_path, f.js_channel));
  for (const auto& p : pairs) {
    if (p.commands.empty())
      throw ModelError(fmt::format("{}: no float64_t messages on {} (the command channel of {})", f.log_path,
                                   p.channel, p.joint));
    const std::string mixed = by_log ? "" : tools::mixed_clocks(f.js_channel, states.front().utime, p.channel,
                                                                p.first_utime);
    if (!mixed.empty())
      throw ModelError(fmt::format(
          "{}: {}. Join by the logger's receive times with --time log, or publish the commands on the sim clock "
          "(turret-cmd and bus pub stamp sim time when sim_server's clock is on the bus; turret-cmd --sim-time "
          "ticks on it)",
          f.log_path, mixed));
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
    if (index < 0) throw std::runtime_error(fmt::format("joint '{}' is not in {}", p.joint, f.js_channel));
    if (p.samples == 0)
      throw ModelError(fmt::format("{}: every {} message came before the first command on {}: nothing to compare",
                                   f.log_path, f.js_channel, p.channel));
  }
  const double sim_s = double(states.back().utime - states.front().utime) * 1e-6;
  fmt::print("tracking over {:.6f} s of sim time, {} joint_states messages:\n", sim_s, states.size());
  for (const auto& p : pairs)
    fmt::print("  {}: rms error {:.6f}, max error {:.6f} ({} samples, {} commands on {}, {} samples before the "
               "first command)\n",
               p.joint, p.samples ? std::sqrt(p.sum_sq / double(p.samples)) : 0.0, p.max_abs, p.samples,
               p.commands.size(), p.channel, p.before_first);
  if (!f.no_timing) {
    const double wall_s = double(state_wall.back() - state_wall.front()) * 1e-6;
    fmt::print("timing (varies by machine): {:.3f} s of wall time, real-time factor {:.2f}\n", wall_s,
               wall_s > 0 ? sim_s / wall_s : 0.0);
  }
  return int(kExitOk);
}

}  // namespace lcm_control::tools
