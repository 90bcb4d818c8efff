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
#include <map>
#include <tuple>
#include <unordered_map>
#include <set>
#include <sstream>

#include "bus/bus.hpp"
#include "bus/messages.hpp"
#include "bus/digest.hpp"
#include "controller_manager/hardware.hpp"
#include "controller_manager/input_stamps.hpp"
#include "controller_manager/manager.hpp"
#include "controller_manager/plugins.hpp"
#include "controller_manager/services.hpp"
#include "description/load.hpp"
#include "description/robot_file.hpp"
#include "tools/lib/logs/closed_loop.hpp"
#include "tools/lib/logs/log_file.hpp"
#include "rt/clock.hpp"
#include "tools/lib/messages/fields.hpp"
#include "lcm_control/run_config_t.hpp"
#include "lcm_control/cm_inputs_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "lcm_control/sim_response_t.hpp"

namespace lcm_control::tools {

namespace {

// The `<controller>/command` channels a command source in the manager publishes on itself, from the command_source_t
// requests handed over: a recorded message there is the source's, not an input.
class SourcedChannels {
 public:
  explicit SourcedChannels(const Bus& bus) : bus_(bus), requests_(bus.channel(channels::kCmCommandSource)) {}
  // Whether a recorded input is handed to the manager: not on a sourced channel, nor a request that does not decode.
  bool hand_over(const std::string& channel, const void* data, size_t size) {
    if (sourced_.count(channel)) return false;
    if (channel != requests_) return true;
    command_source_t r;
    if (!decode_guarded(r, data, size)) return false;
    const std::string target = bus_.channel(r.controller + "/command");
    if (r.remove) sourced_.erase(target);
    else sourced_.insert(target);
    return true;
  }

 private:
  const Bus& bus_;
  std::string requests_;
  std::set<std::string> sourced_;
};

// The recorded namespace (unless one was given) and $(arg) values, for reading the recorded files as the run did.
void read_as_recorded(const run_config_t& c, LoadOptions& load) {
  if (load.ns.empty()) load.ns = c.robot_namespace;
  for (const std::string& a : c.args)
    load.args.emplace_back(a.substr(0, a.find('=')), a.find('=') == std::string::npos ? "" : a.substr(a.find('=') + 1));
}

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
    differs(where);
  }
  // A field that is not a number (a text) differs: the divergence, if it is the first.
  void differs(const Divergence& where) {
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

// A log's events in the order they arrived: by their receive time, within a window of kWindow events. A recorder's
// socket can queue two datagrams that came from two processes on two CPUs a few microseconds apart in the other
// order (seen: a hardware/command ahead of the state it answers); the kernel's receive time, which the recorder
// keeps, has them right. Stable: events of one receive time keep the log's order.
class ArrivalOrderedLog {
 public:
  static constexpr size_t kWindow = 256;
  explicit ArrivalOrderedLog(const std::string& path) : log_(path) {}
  bool good() { return log_.good(); }
  // The next event, or nullptr at the end of what could be read whole; valid until the next call.
  const lcm::LogEvent* next() {
    while (!ended_ && window_.size() < kWindow) {
      const lcm::LogEvent* e = log_.next();
      if (!e) {
        ended_ = true;
        break;
      }
      Owned o;  // in the room of an event already handed out, when there is one: no allocation per event
      if (!spare_.empty()) {
        o = std::move(spare_.back());
        spare_.pop_back();
      }
      o.event.eventnum = e->eventnum;
      o.event.timestamp = e->timestamp;
      o.event.channel.assign(e->channel);
      o.event.datalen = e->datalen;
      o.bytes.assign(static_cast<const uint8_t*>(e->data), static_cast<const uint8_t*>(e->data) + e->datalen);
      auto at = window_.end();  // after every event not later than it
      while (at != window_.begin() && std::prev(at)->event.timestamp > o.event.timestamp) --at;
      window_.insert(at, std::move(o));
    }
    if (window_.empty()) return nullptr;
    if (handed_out_) spare_.push_back(std::move(current_));
    handed_out_ = true;
    current_ = std::move(window_.front());
    window_.pop_front();
    current_.event.data = current_.bytes.data();
    return &current_.event;
  }
  // The byte after the last event read whole from the file.
  long end_of_whole() const { return long(log_.end_of_whole()); }

 private:
  struct Owned {
    lcm::LogEvent event;
    std::vector<uint8_t> bytes;
  };
  LogReader log_;
  std::deque<Owned> window_;
  Owned current_;
  bool handed_out_ = false;
  std::vector<Owned> spare_;
  bool ended_ = false;
};

// A controller's output (any of our types): the same bytes, else field by field (decode_fields), the first
// difference named by the field's label (`position[j1]`).
void compare_output(Comparison& cmp, const std::string& channel, const std::vector<uint8_t>& recorded,
                    const std::vector<uint8_t>& replayed) {
  ChannelSummary& c = cmp.channel(channel);
  ++c.compared;
  if (recorded == replayed) return;
  const Decoded a = decode_fields(recorded.data(), recorded.size());
  const Decoded b = decode_fields(replayed.data(), replayed.size());
  Divergence at{channel, -1, 0, "", "", 0, 0};
  for (const Field& f : a.fields)
    if (f.path == "utime") at.utime = f.exact;
  if (!a.ok() || !b.ok() || a.type != b.type || a.fields.size() != b.fields.size()) {
    at.field = !a.ok() || !b.ok() ? "(not one of lcm_control's types)" : a.type != b.type ? "(type)" : "(number of fields)";
    at.recorded = double(a.fields.size());
    at.replayed = double(b.fields.size());
    cmp.mismatch(c, at);
    return;
  }
  bool same = true;
  for (size_t k = 0; k < a.fields.size(); ++k) {
    const Field& x = a.fields[k];
    const Field& y = b.fields[k];
    at.field = x.name();
    if (x.is_text || y.is_text || x.path != y.path) {
      if (x.str != y.str || x.path != y.path) {
        cmp.differs(at);
        same = false;
      }
      continue;
    }
    same = cmp.value(c, at, x.integer ? double(x.exact) : x.value, y.integer ? double(y.exact) : y.value) && same;
  }
  if (!same) ++c.differing;
}

// The controllers' outputs (channels under a configured controller's name that the live manager did not take
// messages on): what the replayed manager publishes and what the log holds, per channel, paired in order and
// compared as both arrive. A pair published at different hardware times (their utime), or a message one side has and
// the other has not by the end (kEndUs before the last state replayed, for what was published as the recording
// stopped), is a divergence.
struct Outputs {
  static constexpr int64_t kEndUs = 20000;
  struct Message {
    int64_t utime = -1;  // -1: its type has none
    std::vector<uint8_t> bytes;
  };
  std::vector<std::string> prefixes;  // "<controller>/"
  std::set<std::string> fed;          // channels replay hands to the manager: inputs, not outputs
  const std::set<std::string>* inputs = nullptr;  // the channels the live manager took messages on
  std::map<std::string, std::pair<std::deque<Message>, std::deque<Message>>> queues;  // recorded, replayed

  bool is_output(const std::string& channel) const {
    if (fed.count(channel) || (inputs && inputs->count(channel))) return false;
    for (const std::string& p : prefixes)
      if (channel.compare(0, p.size(), p) == 0) return true;
    return false;
  }
  static Message message(const void* data, size_t size) {
    Message m;
    const auto* b = static_cast<const uint8_t*>(data);
    m.bytes.assign(b, b + size);
    for (const Field& f : decode_fields(data, size).fields)
      if (f.path == "utime") m.utime = f.exact;
    return m;
  }
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    if (is_output(channel)) queues[channel].second.push_back(message(rb->data, rb->data_size));
  }
  void recorded(const std::string& channel, const void* data, size_t size) {
    queues[channel].first.push_back(message(data, size));
  }
  void compare(Comparison& cmp) {
    for (auto& [channel, q] : queues) {
      if (fed.count(channel)) {  // fed after it was taken for an output: an input after all
        q.first.clear();
        q.second.clear();
        continue;
      }
      for (; !q.first.empty() && !q.second.empty(); q.first.pop_front(), q.second.pop_front()) {
        const Message& a = q.first.front();
        const Message& b = q.second.front();
        if (a.utime != b.utime) {
          ChannelSummary& c = cmp.channel(channel);
          ++c.compared;
          cmp.mismatch(c, {channel, -1, a.utime, "utime (published at another time)", "", double(a.utime),
                           double(b.utime)});
          continue;
        }
        compare_output(cmp, channel, a.bytes, b.bytes);
      }
    }
  }
  // After the last state (its utime): what one side has and the other has not, but the last kEndUs, is a divergence
  // (a message the replay did not publish, or published and the run did not); returns the messages left unpaired.
  int64_t finish(Comparison& cmp, int64_t last_utime) {
    compare(cmp);
    int64_t left = 0;
    for (auto& [channel, q] : queues) {
      left += int64_t(q.first.size() + q.second.size());
      for (const auto* side : {&q.first, &q.second})
        if (!side->empty() && side->front().utime >= 0 && side->front().utime < last_utime - kEndUs) {
          ChannelSummary& c = cmp.channel(channel);
          const bool recorded_only = side == &q.first;
          cmp.mismatch(c, {channel, -1, side->front().utime,
                           recorded_only ? "(a message the run published and the replay did not)"
                                         : "(a message the replay published and the run did not)",
                           "", recorded_only ? 1.0 : 0.0, recorded_only ? 0.0 : 1.0});
        }
    }
    return left;
  }
};

// Decodes a recorded message of type T; throws naming the log, the event and the channel when it is not one.
template <class T>
T decoded(const ReplayOptions& o, const lcm::LogEvent& e) {
  T m;
  if (!decode_guarded(m, e.data, static_cast<size_t>(e.datalen)))  // array lengths checked before they allocate
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
  LogReader log(o.log);
  for (const lcm::LogEvent* e = log.next(); e; e = log.next())
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
  fs::create_directories(dir);
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
// When each recorded input acted: the controller manager's stamps (cm_inputs_t) matched to the log's messages by
// channel, digest and size, each message to the earliest stamp of its kind not yet matched.
struct InputSchedule {
  using Cycle = std::pair<int64_t, int64_t>;  // (session, step)
  bool stamped = false;                       // the log holds stamps: its inputs are fed at their cycles
  std::map<Cycle, std::vector<int64_t>> at;   // the events (their index in the log) to feed before each cycle
  std::unordered_map<int64_t, Cycle> cycle_of;
  int64_t unrecorded = 0;  // inputs a stamp lists that the log does not hold (lost by the recorder)
  std::map<std::string, int64_t> unstamped;  // messages on a stamped channel no stamp lists (not taken in), by channel
  std::set<std::string> stamped_channels;  // channels the manager took messages on: inputs
};

InputSchedule schedule_inputs(const ReplayOptions& o, const Bus& bus, const std::set<std::string>& not_inputs) {
  using Key = std::tuple<std::string, int64_t, int32_t>;  // channel, digest, size
  InputSchedule plan;
  std::map<Key, std::deque<InputSchedule::Cycle>> stamps;
  std::set<std::string> stamped_channels;
  std::vector<std::pair<int64_t, Key>> candidates;
  const std::string inputs_channel = bus.channel(channels::kCmInputs);
  const cm::InputFilter is_input(bus);
  ArrivalOrderedLog log(o.log);
  int64_t index = 0;
  for (const lcm::LogEvent* e = log.next(); e; e = log.next(), ++index) {
    if (e->channel == inputs_channel) {
      cm_inputs_t m;
      if (!decode_guarded(m, e->data, static_cast<size_t>(e->datalen))) continue;  // the main pass names it
      plan.stamped = true;
      for (int32_t k = 0; k < m.num_inputs; ++k) {
        stamps[{m.channel[k], m.digest[k], m.size[k]}].push_back({m.session, m.step});
        stamped_channels.insert(m.channel[k]);
      }
    } else if (!not_inputs.count(e->channel) &&
               is_input(e->channel, e->data, static_cast<size_t>(e->datalen))) {
      candidates.push_back({index, {e->channel, static_cast<int64_t>(message_digest(e->data, e->datalen)),
                                    static_cast<int32_t>(e->datalen)}});
    }
  }
  for (const auto& [event, key] : candidates) {
    auto it = stamps.find(key);
    if (it == stamps.end() || it->second.empty()) {
      if (stamped_channels.count(std::get<0>(key))) ++plan.unstamped[std::get<0>(key)];
      continue;
    }
    plan.at[it->second.front()].push_back(event);
    plan.cycle_of[event] = it->second.front();
    it->second.pop_front();
  }
  for (const auto& [key, left] : stamps) plan.unrecorded += static_cast<int64_t>(left.size());
  plan.stamped_channels = std::move(stamped_channels);
  return plan;
}
}  // namespace

ReplayReport replay_controllers(const ReplayOptions& o) {
  ArrivalOrderedLog log(o.log);
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
    read_as_recorded(*recorded, load);
    const Materialized m = materialize(*recorded, load, scratch.path());
    urdf = m.urdf;
    if (configs.empty()) configs = m.configs;
    report.notes.push_back(fmt::format("the configuration recorded in the log: {}{}", recorded->urdf_path,
                                       recorded->config_paths.empty()
                                           ? ""
                                           : fmt::format(", {}", fmt::join(recorded->config_paths, ", "))));
  }
  RobotModel model = load_robot_model(urdf, configs, load);
  const int64_t started_us = monotonic_us();
  Bus bus("memq://", model.ns);
  ReplayedManager replayed(model, bus);
  cm::ControllerManager& manager = replayed.manager;
  std::deque<joint_state_t>& published = replayed.joint_states;
  const std::string js_channel = bus.channel(channels::kJointStates);
  Outputs outputs;  // compared where the log says which channels are inputs (its stamps)
  bus.lcm().subscribe(".*", &Outputs::on, &outputs);
  const std::string state_channel = bus.channel(channels::kHardwareState);
  const std::string command_channel = bus.channel(channels::kHardwareCommand);
  const std::string source_channel = bus.channel(channels::kCmCommandSource);
  auto pump = [&] { replayed.pump(); };

  Comparison cmp(o.tolerance);
  SourcedChannels sourced(bus);
  std::deque<hardware_command_t> answers;  // the replayed answers to the recorded states, not yet paired
  int64_t unrecorded_answers = 0;          // answers whose recorded hardware/command the log does not hold
  std::deque<joint_state_t> recorded_states;
  bool bound_checked = false;
  auto compare_published = [&] {
    while (!recorded_states.empty() && !published.empty()) {
      compare_states(cmp, js_channel, recorded_states.front(), published.front());
      recorded_states.pop_front();
      published.pop_front();
    }
  };
  // An input handed to the manager (a command source's channel is its own: it publishes there itself).
  auto feed = [&](const std::string& ch, const void* data, size_t size) {
    if (!sourced.hand_over(ch, data, size)) return;
    outputs.fed.insert(ch);
    bus.lcm().publish(ch, data, static_cast<unsigned>(size));
    ++report.fed;
    pump();
  };
  const std::string inputs_channel = bus.channel(channels::kCmInputs);
  const std::string config_channel = bus.channel(channels::kCmConfig);
  const InputSchedule plan =
      schedule_inputs(o, bus, {state_channel, command_channel, js_channel, inputs_channel, config_channel});
  outputs.inputs = &plan.stamped_channels;
  if (plan.stamped)
    for (const ControllerSpec& c : model.controllers) outputs.prefixes.push_back(bus.channel(c.name + "/"));
  // Stamped inputs read but not fed yet, by event index: by the main pass before their cycle, or by `ahead` when
  // their cycle comes first (the recorder saw them after the state the manager took them before).
  std::map<int64_t, std::pair<std::string, std::vector<uint8_t>>> held;
  std::set<int64_t> fed_early;
  ArrivalOrderedLog ahead_log(o.log);
  int64_t ahead_index = -1, index = -1;
  auto keep = [&](int64_t i, const lcm::LogEvent& e) {
    held.emplace(i, std::make_pair(e.channel, std::vector<uint8_t>(static_cast<const uint8_t*>(e.data),
                                                                  static_cast<const uint8_t*>(e.data) + e.datalen)));
  };
  auto feed_cycle = [&](int64_t session, int64_t step) {
    const auto due = plan.at.find({session, step});
    if (due == plan.at.end()) return;
    for (const int64_t i : due->second) {
      if (!held.count(i)) {
        for (const lcm::LogEvent* e = nullptr; ahead_index < i && (e = ahead_log.next());) {
          ++ahead_index;
          if (ahead_index > index && plan.cycle_of.count(ahead_index) && !held.count(ahead_index)) keep(ahead_index, *e);
        }
        if (!held.count(i)) continue;  // past the log's readable end
        fed_early.insert(i);
      }
      const auto& [ch, bytes] = held.at(i);
      feed(ch, bytes.data(), bytes.size());
      held.erase(i);
    }
  };
  long last_end = 0;  // the byte after the last event read whole
  int64_t last_state_utime = 0;
  for (const lcm::LogEvent* e = log.next(); e; e = log.next()) {
    ++report.events;
    ++index;
    last_end = log.end_of_whole();
    const std::string& ch = e->channel;
    if (plan.stamped && plan.cycle_of.count(index)) {  // fed before the cycle the manager took it in at
      if (!fed_early.erase(index) && !held.count(index)) keep(index, *e);
      continue;
    }
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
      if (plan.stamped) feed_cycle(s.session, s.step);
      manager.on_hardware_state(s);
      last_state_utime = s.utime;
      pump();
      answers.push_back(manager.last_command());
      if (answers.size() > 1000) {  // a log without the commands (recorded without that channel) keeps none of them
        ++unrecorded_answers;
        answers.pop_front();
      }
      ++report.states;
      compare_published();
      outputs.compare(cmp);
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
    } else if (ch == inputs_channel || ch == config_channel) {
      if (ch == inputs_channel) decoded<cm_inputs_t>(o, *e);  // a corrupted stamp is named
      continue;
    } else if (plan.stamped && outputs.is_output(ch)) {
      outputs.recorded(ch, e->data, static_cast<size_t>(e->datalen));
      outputs.compare(cmp);
    } else if (plan.stamped) {
      continue;  // the manager did not take it in (no stamp lists it)
    } else {
      if (ch == source_channel) decoded<command_source_t>(o, *e);
      feed(ch, e->data, static_cast<size_t>(e->datalen));
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
  if (const int64_t n = outputs.finish(cmp, last_state_utime); n > 0)
    report.notes.push_back(fmt::format("{} controller output message(s) at the end have no counterpart (published as "
                                       "the recording stopped): not compared",
                                       n));
  if (plan.stamped) {
    const size_t never = held.size();  // stamped for a cycle the log does not hold
    report.notes.push_back(fmt::format("inputs fed at the cycle the controller manager took them in at ({})", inputs_channel));
    if (plan.unrecorded > 0)
      report.notes.push_back(fmt::format("{} input(s) the controller manager took in are not in the log (lost by the "
                                         "recorder): not fed",
                                         plan.unrecorded));
    if (!plan.unstamped.empty()) {
      std::vector<std::string> where;
      for (const auto& [channel, n] : plan.unstamped) where.push_back(fmt::format("{} on {}", n, channel));
      report.notes.push_back(fmt::format("message(s) on input channels that the controller manager did not take in "
                                         "(lost on their way to it, or sent before it listened): {}; not fed",
                                         fmt::join(where, ", ")));
    }
    if (never > 0)
      report.notes.push_back(fmt::format("{} input(s) stamped for cycles after the log's last state: not fed", never));
  } else {
    report.notes.push_back(fmt::format("inputs fed in the log's order (no {} in it: recorded by a controller "
                                       "manager that reads the bus through LCM, or a version before it)",
                                       inputs_channel));
  }
  unrecorded_answers += std::max<int64_t>(0, static_cast<int64_t>(answers.size()) - 1);  // the last: after the end
  if (unrecorded_answers > 0)
    report.notes.push_back(fmt::format("{} answer(s) to recorded states have no hardware/command in the log (lost by "
                                       "the recorder): not compared",
                                       unrecorded_answers));
  report.channels = cmp.channels_;
  report.first = cmp.first_;
  report.replay_s = double(monotonic_us() - started_us) * 1e-6;
  return report;
}

ReplayReport replay_closed_loop(const ReplayOptions& o) {
  ArrivalOrderedLog log(o.log);
  if (!log.good()) throw ReplayInputError(fmt::format("{}: cannot open the log: {}", o.log, std::strerror(errno)));
  ReplayReport report;
  LoadOptions load = o.load;
  TempDir scratch;
  const std::string prefix = load.ns.empty() ? "" : normalize_namespace(load.ns) + "/";
  const std::optional<run_config_t> cm_config = recorded_config(o, prefix + channels::kCmConfig);
  const std::optional<run_config_t> sim_config = recorded_config(o, prefix + channels::kSimConfig);
  if (!cm_config || !sim_config)
    throw ReplayInputError(fmt::format("{}: a closed-loop replay needs both programs' recorded configurations ({} and "
                                       "{}); record with bus record from this version on",
                                       o.log, prefix + channels::kCmConfig, prefix + channels::kSimConfig));
  read_as_recorded(*cm_config, load);
  const Materialized cm_files = materialize(*cm_config, load, scratch.path() + "/cm");
  const Materialized sim_files = materialize(*sim_config, load, scratch.path() + "/sim");
  report.notes.push_back(fmt::format("closed loop: sim_server as recorded ({})", fmt::join(sim_config->argv, " ")));

  // sim_server's flags as it was started, its files replaced by the recorded texts.
  sim::ProgramFlags flags;
  try {
    flags = parse_sim_command_line(sim_config->argv);
  } catch (const CLI::ParseError& e) {
    throw ReplayInputError(fmt::format("{}: sim_server's recorded command line ({}) is not this version's: {}", o.log,
                                       fmt::join(sim_config->argv, " "), e.what()));
  }
  if (flags.mode != "lockstep")
    throw ReplayInputError(fmt::format("{}: recorded in real time (sim_server --mode {}): its cycles followed the wall "
                                       "clock, which a closed loop cannot repeat; replay it open loop: --controllers "
                                       "(with --tolerance)",
                                       o.log, flags.mode));
  // A --urdf or --config given replaces the recorded files on both sides (one robot, one controllers YAML).
  const std::string urdf = o.urdf.empty() ? cm_files.urdf : o.urdf;
  const std::vector<std::string> cm_configs = o.configs.empty() ? cm_files.configs : o.configs;
  flags.robot.files.urdf = o.urdf.empty() ? sim_files.urdf : o.urdf;
  flags.robot.files.config = o.configs.empty() ? sim_files.configs : o.configs;
  LoadOptions sim_load = load;
  sim_load.config_from_plugin = true;
  const RobotModel model = load_robot_model(urdf, cm_configs, load);
  ClosedLoop loop(flags, sim_load, model);
  const int64_t started_us = monotonic_us();
  Bus& bus = loop.bus();
  std::deque<joint_state_t>& published = loop.manager().joint_states;
  const std::string js_channel = bus.channel(channels::kJointStates);
  const std::string state_channel = bus.channel(channels::kHardwareState);
  const std::string command_channel = bus.channel(channels::kHardwareCommand);
  const std::string inputs_channel = bus.channel(channels::kCmInputs);
  const InputSchedule schedule = schedule_inputs(o, bus, {state_channel, command_channel, js_channel, inputs_channel,
                                                          bus.channel(channels::kCmConfig),
                                                          bus.channel(channels::kSimConfig)});
  if (!schedule.stamped)
    throw ReplayInputError(fmt::format("{}: no {} in the log: a closed loop needs the cycles the inputs were taken at",
                                       o.log, inputs_channel));
  // The recorded inputs by cycle, the recorded commands by step, the recorded joint_states in order; the recorded
  // session (the first) is the replayed one.
  std::map<InputSchedule::Cycle, std::vector<std::pair<std::string, std::vector<uint8_t>>>> inputs_at;
  std::map<int64_t, hardware_command_t> recorded_commands;
  std::deque<joint_state_t> recorded_states;
  const std::string request_channel = bus.channel(channels::kSimRequest), response_channel = bus.channel(channels::kSimResponse);
  std::vector<sim_request_t> sim_requests;  // what sim_server was asked, in the log's order,
  std::map<int64_t, int64_t> served_at;     // and, by request id, the step its answer says it was served at (-1: refused)
  int64_t session = -1, last_step = -1, index = -1;
  for (const lcm::LogEvent* e = log.next(); e; e = log.next()) {
    ++index;
    ++report.events;
    if (e->channel == state_channel) {
      const hardware_state_t st = decoded<hardware_state_t>(o, *e);
      if (session < 0) {  // the robot of the log is the configuration's: every actuator matched by name
        cm::Hardware hw(model);
        hardware_command_t scratch;
        if (const std::string why = hw.bind(st, scratch); !why.empty())
          throw ReplayInputError(fmt::format("{}: the recorded robot is not {}'s: {}", o.log, urdf, why));
        session = st.session;
      }
      if (st.session == session) last_step = std::max(last_step, st.step);
    } else if (e->channel == command_channel) {
      const hardware_command_t c = decoded<hardware_command_t>(o, *e);
      recorded_commands[c.step] = c;
    } else if (e->channel == js_channel) {
      recorded_states.push_back(decoded<joint_state_t>(o, *e));
    } else if (e->channel == request_channel) {
      const sim_request_t r = decoded<sim_request_t>(o, *e);
      if (r.op != sim_request_t::STATUS && r.op != sim_request_t::CONFIG) sim_requests.push_back(r);
    } else if (e->channel == response_channel) {
      const sim_response_t r = decoded<sim_response_t>(o, *e);
      served_at.emplace(r.request_id, r.ok ? r.step : -1);  // the first answer: a repeated request is answered again
    }
    const auto cycle = schedule.cycle_of.find(index);
    if (cycle != schedule.cycle_of.end())
      inputs_at[cycle->second].emplace_back(
          e->channel, std::vector<uint8_t>(static_cast<const uint8_t*>(e->data),
                                           static_cast<const uint8_t*>(e->data) + e->datalen));
  }
  if (last_step < 0) throw ReplayInputError(fmt::format("{}: no {} messages", o.log, state_channel));
  // sim_server's requests, served between the cycle of the step their answer names and the step after it, as its
  // Stepper serves them in lockstep; what sets sim time back or holds it is not replayed yet.
  std::map<int64_t, std::vector<sim_request_t>> served;
  std::set<int64_t> taken;  // a request sent again (its answer lost) was served once
  for (const sim_request_t& r : sim_requests) {
    const int64_t id = r.request_id;
    const auto at = served_at.find(id);
    if (!taken.insert(id).second || (at != served_at.end() && at->second < 0)) continue;  // again, or refused: nothing done
    if (r.op != sim_request_t::APPLY_WRENCH)
      throw ReplayInputError(fmt::format("{}: sim_server was asked to {} (request {}): a closed loop replays "
                                         "wrenches only, not pauses, steps, resets or failed components yet; replay it "
                                         "open loop: --controllers",
                                         o.log, r.op == sim_request_t::PAUSE     ? "pause"
                                                : r.op == sim_request_t::RESUME ? "resume"
                                                : r.op == sim_request_t::STEP   ? "step"
                                                : r.op == sim_request_t::RESET  ? "reset"
                                                                                : "fail a component",
                                         id));
    if (at == served_at.end())
      throw ReplayInputError(fmt::format("{}: the log holds sim_server's request {} (a wrench on '{}') but not its "
                                         "answer on {}, which says the step it acted at: record the whole bus",
                                         o.log, id, r.link, response_channel));
    if (at->second >= 0) served[at->second].push_back(r);
  }
  Comparison cmp(o.tolerance);
  SourcedChannels sourced(bus);
  while (loop.step() <= last_step) {
    const int64_t step = loop.step();
    if (const auto due = inputs_at.find({session, step}); due != inputs_at.end())
      for (const auto& [ch, bytes] : due->second) {
        if (!sourced.hand_over(ch, bytes.data(), bytes.size())) continue;
        bus.lcm().publish(ch, bytes.data(), static_cast<unsigned>(bytes.size()));
        ++report.fed;
      }
    hardware_command_t answer = loop.cycle();
    ++report.states;
    if (const auto rec = recorded_commands.find(step); rec != recorded_commands.end()) {
      answer.session = rec->second.session;  // the replayed simulator's session is a new one
      compare_commands(cmp, command_channel, rec->second, answer);
    }
    while (!recorded_states.empty() && !published.empty()) {
      compare_states(cmp, js_channel, recorded_states.front(), published.front());
      recorded_states.pop_front();
      published.pop_front();
    }
    if (step == last_step) break;
    if (const auto due = served.find(step); due != served.end())
      for (const sim_request_t& r : due->second) {
        loop.serve(r);
        ++report.fed;
      }
    loop.advance();
  }
  report.channels = cmp.channels_;
  report.first = cmp.first_;
  report.replay_s = double(monotonic_us() - started_us) * 1e-6;
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
  out += fmt::format("  ({} log events, {} inputs handed to the controller manager; re-driven in {:.3f} s)\n", r.events,
                     r.fed, r.replay_s);
  return out;
}

}  // namespace lcm_control::tools
