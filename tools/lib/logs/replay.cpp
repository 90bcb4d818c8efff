#include "tools/lib/logs/replay.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <stdlib.h>
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "bus/bus.hpp"
#include "bus/messages.hpp"
#include "controller_manager/hardware.hpp"
#include "controller_manager/manager.hpp"
#include "controller_manager/plugins.hpp"
#include "controller_manager/services.hpp"
#include "description/load.hpp"
#include "description/robot_file.hpp"
#include "lcm_control/run_config_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"

namespace lcm_control::tools {

namespace {

// Keeps what the replayed manager publishes on joint_states, in order.
struct Published {
  std::deque<joint_state_t> joint_states;
  void on(const lcm::ReceiveBuffer*, const std::string&, const joint_state_t* m) { joint_states.push_back(*m); }
};

// A folder of its own under the system's temporary directory, removed with what is in it.
class TempDir {
 public:
  TempDir() {
    std::string pattern = (std::filesystem::temp_directory_path() / "lcm_control_replay_XXXXXX").string();
    if (mkdtemp(pattern.data())) path_ = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    if (!path_.empty()) std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const {
    if (path_.empty()) throw ReplayInputError("cannot make a temporary folder for the recorded configuration");
    return path_;
  }

 private:
  std::string path_;
};

class Comparison {
 public:
  explicit Comparison(double tolerance) : tolerance_(tolerance) {}

  ChannelSummary& channel(const std::string& name) {
    for (ChannelSummary& c : channels_)
      if (c.channel == name) return c;
    channels_.push_back({name, 0, 0, 0});
    return channels_.back();
  }
  // One value: counted into the channel's largest difference; the first beyond the tolerance is the divergence.
  bool value(ChannelSummary& c, const Divergence& where, double recorded, double replayed) {
    const bool same = std::memcmp(&recorded, &replayed, sizeof(double)) == 0 ||
                      (std::isnan(recorded) && std::isnan(replayed));
    if (same) return true;
    const double d = std::isfinite(recorded) && std::isfinite(replayed) ? std::abs(recorded - replayed) : INFINITY;
    c.max_abs = std::max(c.max_abs, d);
    if (d <= tolerance_) return true;
    if (!first_) {
      first_ = where;
      first_->recorded = recorded;
      first_->replayed = replayed;
    }
    return false;
  }
  // A message that has no counterpart (a count or a name that differs): a divergence with no values.
  void mismatch(ChannelSummary& c, const Divergence& where) {
    ++c.differing;
    c.max_abs = INFINITY;
    if (!first_) first_ = where;
  }

  std::vector<ChannelSummary> channels_;
  std::optional<Divergence> first_;

 private:
  double tolerance_;
};

std::string actuator_name(const hardware_command_t& c, size_t k) {
  return k < c.name.size() ? c.name[k] : std::to_string(k);
}

void compare_commands(Comparison& cmp, const std::string& channel, const hardware_command_t& recorded,
                      const hardware_command_t& replayed) {
  ChannelSummary& c = cmp.channel(channel);
  ++c.compared;
  Divergence at{channel, recorded.step, recorded.utime, "", "", 0, 0};
  if (replayed.step != recorded.step || replayed.session != recorded.session ||
      replayed.num_actuators != recorded.num_actuators) {
    at.field = replayed.step != recorded.step ? "step (no answer to it)" : "num_actuators";
    at.recorded = double(replayed.step != recorded.step ? recorded.step : recorded.num_actuators);
    at.replayed = double(replayed.step != recorded.step ? replayed.step : replayed.num_actuators);
    cmp.mismatch(c, at);
    return;
  }
  bool same = true;
  for (size_t k = 0; k < size_t(recorded.num_actuators); ++k) {
    at.index = actuator_name(recorded, k);
    at.field = "mode";
    same = cmp.value(c, at, recorded.mode[k], replayed.mode[k]) && same;
    at.field = "command";
    same = cmp.value(c, at, recorded.command[k], replayed.command[k]) && same;
    at.field = "damping";
    same = cmp.value(c, at, recorded.damping[k], replayed.damping[k]) && same;
  }
  if (!same) ++c.differing;
}

void compare_states(Comparison& cmp, const std::string& channel, const joint_state_t& recorded,
                    const joint_state_t& replayed) {
  ChannelSummary& c = cmp.channel(channel);
  ++c.compared;
  Divergence at{channel, -1, recorded.utime, "", "", 0, 0};
  if (recorded.name != replayed.name || recorded.utime != replayed.utime) {
    at.field = recorded.utime != replayed.utime ? "utime" : "name";
    at.recorded = double(recorded.utime);
    at.replayed = double(replayed.utime);
    cmp.mismatch(c, at);
    return;
  }
  bool same = true;
  const std::pair<const char*, const std::vector<double> joint_state_t::*> fields[] = {
      {"position", &joint_state_t::position}, {"velocity", &joint_state_t::velocity}, {"effort", &joint_state_t::effort}};
  for (const auto& [field, member] : fields) {
    const std::vector<double>& a = recorded.*member;
    const std::vector<double>& b = replayed.*member;
    at.field = field;
    for (size_t k = 0; k < a.size() && k < b.size(); ++k) {
      at.index = k < recorded.name.size() ? recorded.name[k] : std::to_string(k);
      same = cmp.value(c, at, a[k], b[k]) && same;
    }
  }
  if (!same) ++c.differing;
}

// Decodes a recorded message of type T; throws naming the log, the event and the channel when it is not one.
template <class T>
T decoded(const ReplayOptions& o, const lcm::LogEvent& e) {
  T m;
  if (m.decode(e.data, 0, e.datalen) != e.datalen)
    throw ReplayInputError(fmt::format("{}: event {} on '{}' does not decode as {} ({} bytes): a corrupted log, or "
                                       "another program's messages on that channel",
                                       o.log, e.eventnum, e.channel, T::getTypeName(), e.datalen));
  return m;
}


std::string file_text_or_empty(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The run's configuration recorded in the log (run_config_t on `channel`), the first one; nullopt when there is none.
std::optional<run_config_t> recorded_config(const ReplayOptions& o, const std::string& channel) {
  lcm::LogFile log(o.log, "r");
  for (const lcm::LogEvent* e = log.readNextEvent(); e; e = log.readNextEvent())
    if (e->channel == channel) return decoded<run_config_t>(o, *e);
  return std::nullopt;
}

// Where the recorded files are read from: each one's own path when it still holds the recorded text (relative
// references in it keep working), else a copy in `dir`.
struct Materialized {
  std::string urdf;
  std::vector<std::string> configs;
};
Materialized materialize(const run_config_t& c, const LoadOptions& options, const std::string& dir) {
  namespace fs = std::filesystem;
  Materialized m;
  auto write = [&](const std::string& name, const std::string& text) {
    const std::string path = (fs::path(dir) / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  };
  std::string same;
  try {
    same = fs::is_regular_file(c.urdf_path) ? read_robot_file(c.urdf_path, options) : "";
  } catch (const std::exception&) {
    same.clear();  // it no longer expands: the recorded expansion is used
  }
  m.urdf = same == c.urdf ? c.urdf_path : write("recorded.urdf", c.urdf);
  for (size_t k = 0; k < c.configs.size() && k < c.config_paths.size(); ++k)
    m.configs.push_back(file_text_or_empty(c.config_paths[k]) == c.configs[k]
                            ? c.config_paths[k]
                            : write(fmt::format("recorded_{}_{}", k, fs::path(c.config_paths[k]).filename().string()),
                                    c.configs[k]));
  return m;
}
}  // namespace

ReplayReport replay_controllers(const ReplayOptions& o) {
  lcm::LogFile log(o.log, "r");
  if (!log.good()) throw ReplayInputError(fmt::format("{}: cannot open the log: {}", o.log, std::strerror(errno)));
  ReplayReport report;
  std::string urdf = o.urdf;
  std::vector<std::string> configs = o.configs;
  LoadOptions load = o.load;
  TempDir scratch;
  if (urdf.empty()) {  // the configuration the run recorded (controller_manager/config)
    const std::string channel = (load.ns.empty() ? "" : normalize_namespace(load.ns) + "/") + channels::kCmConfig;
    const std::optional<run_config_t> recorded = recorded_config(o, channel);
    if (!recorded)
      throw ReplayInputError(fmt::format("{}: this log carries no recorded configuration (no {} message: recorded "
                                         "without that channel, or by a version before it); give the run's robot and "
                                         "controllers with --urdf FILE --config FILE",
                                         o.log, channel));
    if (load.ns.empty()) load.ns = recorded->robot_namespace;
    for (const std::string& a : recorded->args)
      load.args.emplace_back(a.substr(0, a.find('=')), a.find('=') == std::string::npos ? "" : a.substr(a.find('=') + 1));
    const Materialized m = materialize(*recorded, load, scratch.path());
    urdf = m.urdf;
    if (configs.empty()) configs = m.configs;
    report.notes.push_back(fmt::format("the configuration recorded in the log: {}{}", recorded->urdf_path,
                                       recorded->config_paths.empty()
                                           ? ""
                                           : fmt::format(", {}", fmt::join(recorded->config_paths, ", "))));
  }
  RobotModel model = load_robot_model(urdf, configs, load);
  Bus bus("memq://", model.ns);
  cm::Registry registry = cm::builtin_registry();
  cm::load_plugins(registry, cm::plugin_libraries(model));
  cm::ControllerManager manager(model, bus, registry);
  cm::Services services(manager, bus);
  struct Shutdown {  // the manager answers what is pending while the services that answer are still there
    cm::ControllerManager& m;
    ~Shutdown() { m.shutdown(); }
  } shutdown{manager};
  Published published;
  const std::string js_channel = bus.channel(channels::kJointStates);
  bus.lcm().subscribe(js_channel, &Published::on, &published);
  const std::string state_channel = bus.channel(channels::kHardwareState);
  const std::string command_channel = bus.channel(channels::kHardwareCommand);
  const std::string source_channel = bus.channel("controller_manager/command_source");
  auto pump = [&] {
    for (bool more = true; more;) {
      manager.flush_published();
      more = false;
      while (bus.lcm().handleTimeout(0) > 0) more = true;
    }
  };

  Comparison cmp(o.tolerance);
  std::set<std::string> sourced;  // `<controller>/command` channels a command source in the manager publishes itself
  std::deque<hardware_command_t> answers;  // the replayed answers to the recorded states, not yet paired
  int64_t unrecorded_answers = 0;          // answers whose recorded hardware/command the log does not hold
  std::deque<joint_state_t> recorded_states;
  bool bound_checked = false;
  auto compare_published = [&] {
    while (!recorded_states.empty() && !published.joint_states.empty()) {
      compare_states(cmp, js_channel, recorded_states.front(), published.joint_states.front());
      recorded_states.pop_front();
      published.joint_states.pop_front();
    }
  };
  long last_end = 0;  // the byte after the last event read whole
  for (const lcm::LogEvent* e = log.readNextEvent(); e; e = log.readNextEvent()) {
    ++report.events;
    last_end = std::ftell(log.getFilePtr());
    const std::string& ch = e->channel;
    if (ch == state_channel) {
      const hardware_state_t s = decoded<hardware_state_t>(o, *e);
      if (const std::string why = check(s); !why.empty())
        throw ReplayInputError(fmt::format("{}: event {} on '{}': {}", o.log, e->eventnum, ch, why));
      if (!bound_checked) {  // the robot of the log is the configuration's: every actuator matched by name
        cm::Hardware hw(model);
        hardware_command_t scratch;
        if (const std::string why = hw.bind(s, scratch); !why.empty())
          throw ReplayInputError(fmt::format("{}: the recorded robot is not {}'s: {}", o.log, urdf, why));
        bound_checked = true;
      }
      pump();
      manager.on_hardware_state(s);
      pump();
      answers.push_back(manager.last_command());
      if (answers.size() > 1000) {  // a log without the commands (recorded without that channel) keeps none of them
        ++unrecorded_answers;
        answers.pop_front();
      }
      ++report.states;
      compare_published();
    } else if (ch == command_channel) {
      const hardware_command_t recorded = decoded<hardware_command_t>(o, *e);
      if (report.states == 0) continue;  // the answer to a state from before the recording began
      // Each recorded command with the replayed answer to the same state: one of a real-time run may come after the
      // next state; one whose state the log does not hold means the recorder lost that state, an input.
      while (!answers.empty() && (answers.front().session != recorded.session || answers.front().step < recorded.step)) {
        ++unrecorded_answers;
        answers.pop_front();
      }
      if (answers.empty() || answers.front().step != recorded.step)
        throw ReplayInputError(fmt::format(
            "{}: the recording lost the hardware/state of step {} (event {} is the controller manager's answer to it, "
            "and the log holds no such state): what the controllers were given cannot be replayed. Record again: bus "
            "record asks for the kernel's largest receive buffer (net.core.rmem_max, which scripts/setup raises to "
            "8 MiB); lcm-logger takes `?recv_buf_size=` in its URL; leave the recorder a CPU",
            o.log, recorded.step, e->eventnum));
      compare_commands(cmp, ch, recorded, answers.front());
      answers.pop_front();
    } else if (ch == js_channel) {
      recorded_states.push_back(decoded<joint_state_t>(o, *e));
      compare_published();
    } else if (ch.rfind(bus.channel("hardware/"), 0) == 0 || ch.rfind(bus.channel("sim_server/"), 0) == 0) {
      continue;  // the hardware's side of the loop and the simulator's services: not the manager's inputs
    } else if (sourced.count(ch)) {
      continue;  // the manager's command source publishes it again itself
    } else {
      if (ch == source_channel) {
        const command_source_t r = decoded<command_source_t>(o, *e);
        const std::string target = bus.channel(r.controller + "/command");
        if (r.remove) sourced.erase(target);
        else sourced.insert(target);
      }
      bus.lcm().publish(ch, e->data, static_cast<unsigned>(e->datalen));
      ++report.fed;
      pump();
    }
  }
  {  // the reader stops at an event it cannot read whole: say where
    const long at = last_end;
    std::error_code ec;
    const auto size = std::filesystem::file_size(o.log, ec);
    if (!ec && at >= 0 && static_cast<uintmax_t>(at) < size)
      throw ReplayInputError(fmt::format("{}: truncated or corrupted after event {} (byte {} of {}): nothing past it "
                                         "can be read; record the run again, or replay a copy cut before it",
                                         o.log, report.events, at, size));
  }
  if (report.states == 0)
    throw ReplayInputError(fmt::format("{}: no {} messages in {} events: record the run with its hardware loop (bus "
                                       "record on the robot's bus; a hardware loop on its own URL, --hardware-url, "
                                       "is not on it)",
                                       o.log, state_channel, report.events));
  unrecorded_answers += std::max<int64_t>(0, static_cast<int64_t>(answers.size()) - 1);  // the last: after the end
  if (unrecorded_answers > 0)
    report.notes.push_back(fmt::format("{} answer(s) to recorded states have no hardware/command in the log (lost by "
                                       "the recorder): not compared",
                                       unrecorded_answers));
  report.channels = cmp.channels_;
  report.first = cmp.first_;
  return report;
}

std::string replay_report_text(const ReplayReport& r, double tolerance) {
  std::string out;
  for (const std::string& n : r.notes) out += "note: " + n + "\n";
  if (r.first) {
    const Divergence& d = *r.first;
    out += fmt::format("diverged: first on {} at {}{}, {}{}: recorded {:.17g}, replayed {:.17g}\n", d.channel,
                       d.step >= 0 ? fmt::format("step {} ", d.step) : "", fmt::format("t={:.6f} s", d.utime * 1e-6),
                       d.field, d.index.empty() ? "" : "[" + d.index + "]", d.recorded, d.replayed);
  } else {
    out += tolerance > 0 ? fmt::format("within tolerance {:g}: ", tolerance) : "identical: ";
    out += fmt::format("{} hardware states replayed, every compared message {}\n", r.states,
                       tolerance > 0 ? "within it" : "bit for bit");
  }
  for (const ChannelSummary& c : r.channels)
    out += fmt::format("  {}: {} compared, {} differ, max |difference| {:.3g}\n", c.channel, c.compared, c.differing,
                       c.max_abs);
  out += fmt::format("  ({} log events, {} inputs handed to the controller manager)\n", r.events, r.fed);
  return out;
}

}  // namespace lcm_control::tools
