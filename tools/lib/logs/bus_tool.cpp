#include "tools/lib/logs/bus_tool.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <regex>
#include <set>
#include <utility>
#include <vector>

#include "bus/messages.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "rt/clock.hpp"
#include "description/text.hpp"
#include "tools/lib/clients/census.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/messages/csv.hpp"
#include "tools/lib/messages/fields.hpp"
#include "tools/lib/messages/message_text.hpp"
#include "tools/lib/clients/netcheck.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/logs/log_file.hpp"
#include "tools/lib/clients/time_base.hpp"

namespace lcm_control::tools {

namespace {

std::string rate_text(double hz) { return hz >= 100 ? fmt::format("{:.0f}", hz) : fmt::format("{:.1f}", hz); }

std::string bytes_text(double b) {
  if (b >= 1e6) return fmt::format("{:.1f} MB", b / 1e6);
  if (b >= 1e3) return fmt::format("{:.1f} KB", b / 1e3);
  return fmt::format("{:.0f} B", b);
}

[[noreturn]] void nothing_on(const std::string& channel, const Bus& bus, const Census& census) {
  const bool hardware = channel.find(channels::kHardwareState) != std::string::npos ||
                        channel.find(channels::kHardwareCommand) != std::string::npos;
  throw BusError(fmt::format("no message on '{}' ({}); channels seen: {}. Check the channel name, --namespace and "
                             "--lcm-url (or LCM_DEFAULT_URL){}",
                             channel, bus.url(), census.names(),
                             hardware ? "; a robot's hardware loop may have a URL of its own: add --hardware-url "
                                        "auto (or the URL sim_server's ready line gives)"
                                      : ""));
}

// Runs the bus until stop(), Ctrl-C or `duration` seconds (0: no limit); every 5 s without a message on
// `channel` (or on any of `also`), says which channels it did see.
template <class Stop>
void run_until(Bus& bus, const Census& census, const std::string& channel, double duration, Stop&& stop,
               const std::vector<std::string>& also = {}) {
  const int64_t start = monotonic_us();
  int64_t next_hint = start + 5000000;
  NamespaceProbe other_ns(bus, {channel.substr(bus.channel("").size())});  // says at once when heard elsewhere
  bool hinted = false;
  while (!stop_requested() && !stop()) {
    const int64_t now = monotonic_us();
    if (duration > 0 && now - start >= int64_t(duration * 1e6)) break;
    if (!hinted && !census.seen().count(channel))
      if (const std::string h = other_ns.hint(); !h.empty()) {
        fmt::print(stderr, "bus: no message on '{}'; {}\n", channel, h);
        hinted = true;
      }
    if (now >= next_hint) {
      const bool heard = census.seen().count(channel) ||
                         std::any_of(also.begin(), also.end(), [&](const auto& c) { return census.seen().count(c); });
      if (!heard)
        fmt::print(stderr, "bus: no message on '{}' yet; channels seen: {}\n", channel, census.names());
      next_hint = now + 5000000;
    }
    handle_bus(bus, 50);
  }
}

int cmd_list(Bus& bus, double duration) {
  Census census(bus);
  const int64_t start = monotonic_us();
  pump_until(bus, [] { return false; }, duration);
  const int64_t window = monotonic_us() - start;
  if (census.seen().empty())
    throw BusError(fmt::format("no messages on {} in {}: is anything running with this --lcm-url / LCM_DEFAULT_URL{}?",
                               bus.url(), seconds_text(duration),
                               bus.ns().empty() ? "" : " in namespace " + bus.ns()));
  size_t width = 7;
  for (const auto& [name, s] : census.seen()) width = std::max(width, name.size());
  fmt::print("{:<{}}  {:<42} {:>8} {:>9} {:>12}\n", "CHANNEL", width, "TYPE", "MSGS", "RATE Hz", "BANDWIDTH");
  for (const auto& [name, s] : census.seen())
    fmt::print("{:<{}}  {:<42} {:>8} {:>9} {:>10}/s\n", name, width, s.type, s.count, rate_text(s.rate(window)),
               bytes_text(double(s.bytes) * 1e6 / double(window)));
  fmt::print("{} channels over {:.1f} s on {}\n", census.seen().size(), double(window) * 1e-6, bus.url());
  if (census.unlisted() > 0)
    fmt::print("and {} messages on channels past the first {} (not listed: each program keeps at most that many "
               "names)\n",
               census.unlisted(), Census::kMaxChannels);
  return kExitOk;
}

class RateMeter {
 public:
  RateMeter(Bus& bus, const std::string& channel, size_t window) : window_(window) {
    bus.subscribe(regex_escape(channel), &RateMeter::on, this, Bus::On::Shared, 10000);
  }
  int64_t total() const { return total_; }
  int64_t fresh() const { return total_ - reported_; }  // messages since the last report()
  // One rostopic-hz line for the messages since the last report, over the window.
  std::string report() {
    const int64_t fresh = total_ - reported_;
    reported_ = total_;
    if (fresh == 0) return "no new messages";
    if (periods_.empty()) return fmt::format("{} message", total_);
    double sum = 0, lo = periods_.front(), hi = periods_.front();
    for (double p : periods_) {
      sum += p;
      lo = std::min(lo, p);
      hi = std::max(hi, p);
    }
    const double mean = sum / double(periods_.size());
    double var = 0;
    for (double p : periods_) var += (p - mean) * (p - mean);
    const double sd = std::sqrt(var / double(periods_.size()));
    return fmt::format("average rate: {:.3f} Hz  min {:.3f} ms  max {:.3f} ms  std dev {:.3f} ms  window {}",
                       1e6 / mean, lo * 1e-3, hi * 1e-3, sd * 1e-3, periods_.size() + 1);
  }

 private:
  // Periods between arrival stamps (the socket's receive time), not between handler calls, which a stall of this
  // process would bunch up.
  void on(const lcm::ReceiveBuffer* rb, const std::string&) {
    const int64_t now = rb->recv_utime;
    if (last_ >= 0) {
      periods_.push_back(double(now - last_));
      if (periods_.size() > window_) periods_.pop_front();
    }
    last_ = now;
    ++total_;
  }
  size_t window_;
  std::deque<double> periods_;
  int64_t last_ = -1, total_ = 0, reported_ = 0;
};

int cmd_hz(Bus& bus, const std::string& name, size_t window, double duration) {
  const std::string channel = bus.channel(name);
  Census census(bus);
  RateMeter meter(bus, channel, window);
  int64_t next = monotonic_us() + 1000000;
  const int64_t start = monotonic_us();
  run_until(bus, census, channel, duration, [&] {
    if (monotonic_us() < next) return false;
    next += 1000000;
    if (meter.total() > 0) fmt::print("{}: {}\n", channel, meter.report());
    std::fflush(stdout);
    return false;
  });
  if (meter.total() == 0) nothing_on(channel, bus, census);
  if (meter.fresh() > 0) fmt::print("{}: {}\n", channel, meter.report());  // since the last second's line
  const double seconds = double(monotonic_us() - start) * 1e-6;
  fmt::print("{}: {} messages in {:.1f} s ({:.1f} Hz on average)\n", channel, meter.total(), seconds,
             double(meter.total()) / seconds);
  return kExitOk;
}

// One channel and, optionally, field paths in its messages (`position`, `position[j2]`): what echo prints.
struct EchoTarget {
  std::string channel;
  std::vector<std::string> fields;  // none: the whole message
};

// What `bus echo NAME [--field F]...` may mean: NAME is a channel (its fields F, or the whole message); or, as
// rostopic echo takes /joint_states/position, a channel followed by a field path ('/' between the field's parts as in
// ROS).
std::vector<EchoTarget> echo_targets(const Bus& bus, const std::string& name, const std::vector<std::string>& fields) {
  std::vector<EchoTarget> out{{bus.channel(name), fields}};
  if (!fields.empty()) return out;
  for (size_t cut = name.rfind('/'); cut != std::string::npos && cut > 0; cut = name.rfind('/', cut - 1)) {
    std::string tail = name.substr(cut + 1);
    std::replace(tail.begin(), tail.end(), '/', '.');
    out.push_back({bus.channel(name.substr(0, cut)), {tail}});
  }
  return out;
}

class Echo {
 public:
  Echo(Bus& bus, std::vector<EchoTarget> targets, bool csv) : targets_(std::move(targets)) {
    for (const auto& t : targets_) bus.subscribe(regex_escape(t.channel), &Echo::on, this, Bus::On::Shared, 10000);
    if (csv) csv_ = std::make_unique<CsvWriter>("-");
  }
  int64_t printed() const { return printed_; }
  // Why echo stops without printing (a field the channel's messages do not have), "" while it may go on.
  const std::string& refused() const { return refused_; }

 private:
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    const auto target = std::find_if(targets_.begin(), targets_.end(), [&](const EchoTarget& t) {
      return t.channel == channel;
    });
    if (target == targets_.end() || !refused_.empty()) return;
    if (target != targets_.begin() && heard_whole_) return;  // the whole name is a channel: it wins
    heard_whole_ = heard_whole_ || target == targets_.begin();
    try {
      if (!csv_ && target->fields.empty()) {
        fmt::print("{}---\n", message_yaml(rb->data, rb->data_size));
      } else {
        Decoded d = decode_fields(rb->data, rb->data_size);
        if (!d.ok()) throw std::runtime_error((d.type.empty() ? "" : d.type + ": ") + d.skip_reason);
        if (!target->fields.empty() && !only(d, target->channel, target->fields)) return;
        if (csv_) {
          csv_->write(d.fields);
          csv_->flush();
        } else if (d.fields.size() == 1) {
          fmt::print("{}\n---\n", d.fields[0].text());
        } else {
          for (const auto& f : d.fields) fmt::print("{}: {}\n", f.name(), f.text());
          fmt::print("---\n");
        }
      }
      std::fflush(stdout);
      ++printed_;
    } catch (const std::exception& e) {
      if (skipped_++ == 0 || skipped_ % 1000 == 0)
        fmt::print(stderr, "bus: {}: skipping a message ({} so far): {}\n", channel, skipped_, e.what());
    }
  }
  // Keeps in d the fields `fields` name, in their order (and utime first, for CSV rows); false, and refused() says
  // why, when one names none.
  bool only(Decoded& d, const std::string& channel, const std::vector<std::string>& fields) {
    std::vector<const Field*> picked;
    for (const std::string& field : fields) {
      const std::vector<const Field*> these = select_fields(d.fields, field);
      if (these.empty()) {
        const std::vector<std::string> near = nearest_fields(d.fields, field);
        refused_ = fmt::format("{} messages ({}) have no field '{}'; {}", channel, d.type, field,
                               near.empty() ? "bus types " + short_type_name(d.type) + " lists the fields"
                                            : "nearest: " + join(near));
        return false;
      }
      picked.insert(picked.end(), these.begin(), these.end());
    }
    std::vector<Field> kept;
    if (csv_)
      for (const auto& f : d.fields)
        if (f.path == "utime" && picked.front()->path != "utime") kept.push_back(f);
    for (const Field* f : picked) kept.push_back(*f);
    d.fields = std::move(kept);
    return true;
  }
  std::vector<EchoTarget> targets_;
  std::unique_ptr<CsvWriter> csv_;
  bool heard_whole_ = false;
  std::string refused_;
  int64_t printed_ = 0, skipped_ = 0;
};

int cmd_echo(Bus& bus, const std::string& name, std::vector<std::string> fields, bool csv, int64_t count,
             double duration) {
  const std::string channel = bus.channel(name);
  Census census(bus);
  for (std::string& f : fields) f = without_leading_slashes(f);
  const std::vector<EchoTarget> targets = echo_targets(bus, name, fields);
  std::vector<std::string> also;
  for (const auto& t : targets) also.push_back(t.channel);
  Echo echo(bus, targets, csv);
  run_until(
      bus, census, channel, duration, [&] { return !echo.refused().empty() || (count > 0 && echo.printed() >= count); },
      also);
  if (!echo.refused().empty()) throw std::runtime_error(echo.refused());
  if (echo.printed() == 0) {
    if (census.seen().count(channel))
      throw BusError(fmt::format("'{}' carried {} messages, none of an lcm_control type that decodes ({})", channel,
                                 census.seen().at(channel).count, census.seen().at(channel).type));
    nothing_on(channel, bus, census);
  }
  return kExitOk;
}

int cmd_pub(Bus& bus, const std::string& ros_name, const std::string& type, const std::vector<std::string>& fields,
            double rate, int64_t count) {
  std::optional<cm_response_t> listed;  // the controllers, when the name may be a controller's command channel
  const std::string last = ros_name.substr(ros_name.rfind('/') + 1);
  if (ros_name.find('/') != std::string::npos && ros_name.rfind("hardware/", 0) != 0 &&
      (last == "command" || last == "commands" || last == "joint_trajectory" || last == "cmd_vel" ||
       last == "reference"))
    listed = try_list(bus, "bus", 0.5);
  std::string note;
  const std::string name = channel_from_ros(ros_name, listed ? &listed->controllers : nullptr, &note);
  if (!note.empty()) fmt::print(stderr, "bus: {}\n", note);
  const std::string channel = bus.channel(name);
  const CommandClock clock(bus, 0.3);
  auto make = [&] {
    try {
      return build_message(type, fields, clock.now_us());
    } catch (const std::invalid_argument& e) {
      throw CLI::ValidationError(e.what());
    }
  };
  auto send = [&](const std::vector<uint8_t>& bytes) {
    if (bus.lcm().publish(channel, bytes.data(), unsigned(bytes.size())) != 0)
      throw BusError("could not publish on " + channel + " (" + bus.url() + ")");
  };
  std::vector<uint8_t> bytes = make();
  const std::string full_type = type_of_payload(bytes.data(), bytes.size());
  check_command_channel(bus, name, {full_type.substr(full_type.rfind('.') + 1), 0}, listed ? &*listed : nullptr);
  const char* stamp = clock.on_sim() ? "sim time" : "wall-clock time";
  if (rate <= 0) {
    send(bytes);
    fmt::print(stderr, "bus: published {} on {} ({} bytes, stamped in {})\n", full_type, channel, bytes.size(), stamp);
    return kExitOk;
  }
  fmt::print(stderr, "bus: publishing {} on {} at {} Hz{}, stamped in {}\n", full_type, channel, rate_text(rate),
             count > 0 ? fmt::format(", {} messages", count) : " until Ctrl-C", stamp);
  const int64_t period = std::max<int64_t>(1, int64_t(std::llround(1e6 / rate)));
  int64_t next = monotonic_us(), sent = 0;
  while (!stop_requested() && (count <= 0 || sent < count)) {
    send(sent == 0 ? bytes : make());
    ++sent;
    next += period;
    pump_until(bus, [] { return false; }, double(next - monotonic_us() - 1000) * 1e-6);  // sim time moves on
    sleep_until_us(next);
  }
  fmt::print(stderr, "bus: published {} messages\n", sent);
  return kExitOk;
}

std::string date_text(int64_t utime) {
  const time_t secs = time_t(utime / 1000000);
  std::tm tm{};
  localtime_r(&secs, &tm);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S", &tm);
  return fmt::format("{}.{:06d} ({:.6f})", buf, int(utime % 1000000), double(utime) * 1e-6);
}

int cmd_info(const std::string& path) {
  const auto log_file = open_log(path);
  lcm::LogFile& log = *log_file;
  std::map<std::string, ChannelSeen> seen;
  int64_t messages = 0, first = 0, last = 0;
  while (const lcm::LogEvent* e = log.readNextEvent()) {
    auto& s = seen[e->channel];
    const std::string type = type_name(e->data, size_t(std::max<int32_t>(0, e->datalen)));
    if (s.count++ == 0) {
      s.first_us = e->timestamp;
      s.type = type;
    } else if (s.type != type && s.type.find("mixed") == std::string::npos) {
      s.type += " (mixed types)";
    }
    s.last_us = e->timestamp;
    s.bytes += e->datalen;
    if (messages++ == 0) first = e->timestamp;
    last = std::max(last, e->timestamp);
  }
  if (messages == 0)
    throw ModelError({fmt::format("{}: no events: not a log written by lcm-logger, or an empty one", path)});
  const double duration = double(last - first) * 1e-6;
  fmt::print("path:      {}\n", path);
  fmt::print("size:      {}\n", bytes_text(double(std::filesystem::file_size(path))));
  fmt::print("duration:  {:.3f} s\n", duration);
  fmt::print("start:     {}\n", date_text(first));
  fmt::print("end:       {}\n", date_text(last));
  fmt::print("messages:  {}\n", messages);
  fmt::print("channels:\n");
  size_t width = 7;
  for (const auto& [name, s] : seen) width = std::max(width, name.size());
  for (const auto& [name, s] : seen)
    fmt::print("  {:<{}}  {:>8} msgs  {:>9} Hz  {}\n", name, width, s.count,
               rate_text(s.count >= 2 && s.last_us > s.first_us ? double(s.count - 1) * 1e6 / double(s.last_us - s.first_us)
                                                                 : 0.0),
               s.type);
  return kExitOk;
}

// Writes what arrives into an lcm-logger log: the same events (receive time, channel, bytes), with a queue deep
// enough for a lockstep run, where lcm-logger's 30 messages per subscription last a few ms.
class Recorder {
 public:
  Recorder(Bus& bus, const std::string& regex, const std::string& path) : log_(path, "w") {
    if (!log_.good())
      throw std::runtime_error("cannot write the log '" + path + "': check the folder exists and is writable");
    bus.subscribe(regex, &Recorder::on, this, Bus::On::Shared, 1000000);
  }
  // The next message on `channel` with exactly these bytes is not written: one of the recorder's own requests.
  void leave_out(const std::string& channel, std::vector<uint8_t> bytes) { own_.emplace_back(channel, std::move(bytes)); }
  int64_t events() const { return events_; }
  // Channels recorded, counted up to Census::kMaxChannels (anyone on the bus can invent names): the count, and
  // whether there were more.
  size_t channels() const { return channels_.size(); }
  bool more_channels() const { return more_channels_; }
  int64_t bytes() const { return bytes_; }
  bool failed() const { return failed_; }

 private:
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    for (auto own = own_.begin(); own != own_.end(); ++own) {
      if (channel == own->first && rb->data_size == own->second.size() &&
          std::memcmp(rb->data, own->second.data(), own->second.size()) == 0) {
        own_.erase(own);
        return;
      }
    }
    lcm::LogEvent e{};
    e.eventnum = events_;
    e.timestamp = rb->recv_utime;
    e.channel = channel;
    e.datalen = static_cast<int32_t>(rb->data_size);
    e.data = rb->data;
    if (log_.writeEvent(&e) != 0) {
      failed_ = true;  // not thrown through LCM's C dispatch: cmd_record stops and says so
      return;
    }
    ++events_;
    bytes_ += rb->data_size;
    if (channels_.size() < Census::kMaxChannels || channels_.count(channel))
      ++channels_[channel];
    else
      more_channels_ = true;
  }
  lcm::LogFile log_;
  bool failed_ = false;
  int64_t events_ = 0, bytes_ = 0;
  std::map<std::string, int64_t> channels_;
  bool more_channels_ = false;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> own_;  // leave_out()'s, each left out once
};

// A udpm URL with the receive buffer a recorder wants: the kernel's largest (net.core.rmem_max), up to 8 MiB, unless
// the URL names one. A recorder starved of the CPU for a moment then loses nothing of a lockstep run's burst.
std::string recording_url(const std::string& url) {
  if (url.rfind("udpm://", 0) != 0 || url.find("recv_buf_size=") != std::string::npos) return url;
  long most = 8 << 20;
  if (std::ifstream in("/proc/sys/net/core/rmem_max"); in) {
    long cap = 0;
    if (in >> cap && cap > 0) most = std::min(most, cap);
  }
  return url + (url.find('?') == std::string::npos ? "?" : "&") + "recv_buf_size=" + std::to_string(most);
}

int cmd_record(Bus& bus, const std::string& path, const std::string& regex, bool force, double duration) {
  if (!force && std::filesystem::exists(path))
    throw CLI::ValidationError("LOG", "'" + path + "' exists: give --force to overwrite it, or another file name");
  Recorder rec(bus, regex, path);
  // The controller manager's and sim_server's configurations into the log (each publishes its own at start too), so
  // that the run replays alone; the requests themselves are left out of it.
  auto ask_for = [&](const char* config, const char* request_channel, const auto& ask) {
    if (!std::regex_match(bus.channel(config), std::regex(regex))) return;
    std::vector<uint8_t> bytes(static_cast<size_t>(ask.getEncodedSize()));
    ask.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    rec.leave_out(bus.channel(request_channel), bytes);
    bus.lcm().publish(bus.channel(request_channel), bytes.data(), static_cast<unsigned>(bytes.size()));
  };
  cm_request_t cm_ask = cm_request(cm_request_t::CONFIG, {}, {}, {});
  cm_ask.client = "bus record";
  ask_for(channels::kCmConfig, channels::kCmRequest, cm_ask);
  sim_request_t sim_ask{};
  sim_ask.utime = wall_us();
  sim_ask.request_id = wall_us();
  sim_ask.client = "bus record";
  sim_ask.op = sim_request_t::CONFIG;
  ask_for(channels::kSimConfig, channels::kSimRequest, sim_ask);
  fmt::print("bus record: recording '{}' on {} to {} until Ctrl-C{}\n", regex, bus.url(), path,
             duration > 0 ? fmt::format(" or {}", seconds_text(duration)) : "");
  std::fflush(stdout);
  pump_until(bus, [&] { return rec.failed(); }, duration > 0 ? duration : 1e12);
  while (!rec.failed() && bus.handle_shared(1) > 0) {  // what was queued when the time was up
  }
  if (rec.failed())
    throw std::runtime_error(fmt::format("writing '{}' failed after {} messages (disk full?)", path, rec.events()));
  fmt::print("bus record: {} messages on {}{} channels, {} -> {}\n", rec.events(), rec.more_channels() ? "over " : "",
             rec.channels(),
             bytes_text(double(rec.bytes())), path);
  return kExitOk;
}

// Publishes a log's events on the bus as lcm-logplayer does: on the channels they were recorded on, at the log's
// times scaled by 1/speed (the first event at once), again from the start with `loop`, until the end, Ctrl-C or
// `duration` seconds.
int cmd_play(Bus& bus, const std::string& path, double speed, bool loop, double duration) {
  const int64_t start = monotonic_us();
  const int64_t end = duration > 0 ? start + int64_t(duration * 1e6) : std::numeric_limits<int64_t>::max();
  int64_t published = 0, passes = 0;
  std::set<std::string> channels;
  fmt::print("bus play: {} on {} at {}x real time{}\n", path, bus.url(), speed, loop ? ", looping until Ctrl-C" : "");
  std::fflush(stdout);
  bool more = true;
  while (more && !stop_requested()) {
    const auto log_file = open_log(path);
    const int64_t pass_start = monotonic_us();
    int64_t first = -1, events = 0;
    for (const lcm::LogEvent* e = log_file->readNextEvent(); e; e = log_file->readNextEvent()) {
      if (first < 0) first = e->timestamp;
      const int64_t due = pass_start + int64_t(double(e->timestamp - first) / speed);
      while (!stop_requested() && monotonic_us() < std::min(due, end))
        sleep_until_us(std::min({due, end, monotonic_us() + 50000}));
      if (stop_requested() || monotonic_us() >= end) {
        more = false;
        break;
      }
      if (bus.lcm().publish(e->channel, e->data, unsigned(std::max<int32_t>(0, e->datalen))) != 0)
        throw BusError("could not publish on " + e->channel + " (" + bus.url() + ")");
      ++events;
      ++published;
      if (channels.size() < Census::kMaxChannels) channels.insert(e->channel);
    }
    if (events == 0 && more)
      throw ModelError({fmt::format("{}: no events: not a log written by lcm-logger or bus record, or an empty one",
                                    path)});
    ++passes;
    more = more && loop;
  }
  fmt::print("bus play: {} messages on {} channels{}\n", published, channels.size(),
             passes > 1 ? fmt::format(" ({} passes)", passes) : "");
  return kExitOk;
}

int cmd_types(const std::string& type) {
  if (type.empty()) {
    for (const auto& t : message_type_names()) fmt::print("{}\n", t);
    return kExitOk;
  }
  try {
    for (const auto& f : message_fields(type)) fmt::print("{}\n", f);
  } catch (const std::invalid_argument& e) {
    throw CLI::ValidationError(e.what());
  }
  return kExitOk;
}

}  // namespace

void add_bus_tool_flags(CLI::App& app, BusToolFlags& f) {
  app.require_subcommand(1);
  app.fallthrough();
  add_bus_flags(app, f.bus);
  app.add_option("--hardware-url,--hardware-lcm-url", f.bus.hardware_lcm_url,
                 "listen and publish on a robot's hardware loop instead of the --lcm-url: `auto` for the one "
                 "--hardware-url auto gives the --namespace (as launch --robots does), or its LCM URL (a loop in "
                 "shared memory is seen through sim_server's and controller_manager's --hardware-mirror)");

  f.list = app.add_subcommand("list", "channels seen on the bus: type, messages, rate, bandwidth (like lcm-spy)");
  f.list->add_option("--duration", f.list_duration, "seconds to listen (default 2)")->check(CLI::PositiveNumber);

  f.hz = app.add_subcommand("hz", "a channel's rate each second (rostopic hz)");
  f.hz->add_option("CHANNEL", f.channel, "channel (the namespace is prefixed)")->required();
  f.hz->add_option("--window", f.window, "periods the statistics cover (default 1000)")->check(CLI::PositiveNumber);
  f.hz->add_option("--duration", f.duration, "stop after S seconds")->check(CLI::PositiveNumber);

  f.echo = app.add_subcommand("echo", "a channel's messages, decoded, or one field of them (rostopic echo)");
  f.echo->add_option("CHANNEL", f.channel,
                   "channel (the namespace is prefixed); CHANNEL/FIELD prints that field, as rostopic echo "
                   "/joint_states/position does")
      ->required();
  f.echo->add_option("--field", f.fields,
                   "print only this field (again for more: --field position --field velocity): a path as log2csv's "
                   "columns (position[1], position) or the dashboard's label (position[j2])")
      ->allow_extra_args(false);
  f.echo->add_option("--count", f.count, "stop after N messages")->check(CLI::PositiveNumber);
  f.echo->add_option("--duration", f.duration, "stop after S seconds")->check(CLI::PositiveNumber);
  f.echo->add_flag("--csv", f.csv, "CSV rows (state-logger's columns) instead of YAML");

  f.pub = app.add_subcommand("pub", "publish one lcm_control message built from FIELD=VALUE (rostopic pub)");
  f.pub->add_option("CHANNEL", f.channel, "channel (the namespace is prefixed)")->required();
  f.pub->add_option("TYPE", f.type, "message type, e.g. float64_t (bus types lists them)")->required();
  f.pub->add_option("FIELD=VALUE", f.assignments,
                  "fields by path: data=0.5, position[1]=2, name=[j1,j2], points[0].positions=[0.1,0.2]; "
                  "unset fields are 0 or empty, array lengths follow the arrays, utime defaults to now (sim time when "
                  "sim_server's clock is on the bus)");
  f.pub->add_option("--rate", f.rate, "publish at HZ until Ctrl-C or --count (default: once)")->check(CLI::PositiveNumber);
  f.pub->add_option("--count", f.count, "with --rate: stop after N messages")->check(CLI::PositiveNumber);

  f.types = app.add_subcommand("types", "the message types, or one type's fields as pub takes them");
  f.types->add_option("TYPE", f.type, "a type to describe");

  f.netcheck = app.add_subcommand(
      "netcheck", "does multicast on this URL reach other computers? ttl, route, firewall, and who answers a probe");
  f.netcheck->add_option("--duration", f.net_duration, "seconds to probe (with --answer: 0, the default there, until Ctrl-C)")
      ->check(CLI::NonNegativeNumber);
  f.netcheck->add_flag("--answer", f.answer_only, "only answer the probes of other computers' netcheck");

  f.record = app.add_subcommand(
      "record", "record the bus into a log in lcm-logger's format, losing nothing at lockstep's rates (rosbag record)");
  f.record->add_option("LOG", f.log_path, "log file to write")->required();
  f.record->add_option("-c,--channel", f.record_regex, "channels to record: a regular expression on the whole name "
                                                   "(default .*; the namespace is not prefixed)");
  f.record->add_option("--duration", f.duration, "stop after S seconds (default: at Ctrl-C)")->check(CLI::PositiveNumber);
  f.record->add_flag("-f,--force", f.force, "overwrite LOG");

  f.play = app.add_subcommand("play", "replay a log on the bus at its recorded pace (lcm-logplayer, rosbag play)");
  f.play->add_option("LOG", f.log_path, "log file written by lcm-logger or bus record (played on its channels as "
                                    "recorded: no --namespace prefix)")
      ->required();
  f.play->add_option("-s,--speed", f.speed, "playback speed: 1 real time (default), 2 twice as fast, 0.5 half")
      ->check(CLI::PositiveNumber);
  f.play->add_flag("-l,--loop", f.loop, "start again from the beginning at the end, until Ctrl-C or --duration");
  f.play->add_option("--duration", f.duration, "stop after S seconds")->check(CLI::PositiveNumber);

  f.info = app.add_subcommand("info", "channels, counts, rates and duration of an lcm-logger log (rosbag info)");
  f.info->add_option("LOG", f.log_path, "log file written by lcm-logger")->required();
}

int run_bus_tool(BusToolFlags f) {
  f.channel = without_leading_slashes(f.channel);
  if (f.info->parsed()) return cmd_info(f.log_path);
  if (f.types->parsed()) return cmd_types(f.type);
  install_stop_signals();
  if (is_shm_url(f.bus.hardware_lcm_url))
    throw BusError(fmt::format("--hardware-url {}: bus reads LCM, and a hardware loop in shared memory is not on it; "
                               "start sim_server and controller_manager with --hardware-mirror HZ (launch: "
                               "hardware_mirror: HZ) and read hardware/state on the --lcm-url",
                               f.bus.hardware_lcm_url));
  const std::string url = f.bus.hardware_lcm_url.empty()
                              ? f.bus.lcm_url
                              : hardware_url_for(f.bus.hardware_lcm_url, effective_url(f.bus.lcm_url),
                                                 f.bus.ns);
  Bus bus(f.record->parsed() ? recording_url(effective_url(url)) : url, f.bus.ns, "", HardwareReader::Direct);
  if (f.list->parsed()) return cmd_list(bus, f.list_duration);
  if (f.record->parsed()) return cmd_record(bus, f.log_path, f.record_regex, f.force, f.duration);
  if (f.play->parsed()) return cmd_play(bus, f.log_path, f.speed, f.loop, f.duration);
  if (f.netcheck->parsed())
    return cmd_netcheck(bus, f.answer_only && f.netcheck->count("--duration") == 0 ? 0.0 : f.net_duration, f.answer_only);
  if (f.hz->parsed()) return cmd_hz(bus, f.channel, f.window, f.duration);
  if (f.echo->parsed()) return cmd_echo(bus, f.channel, f.fields, f.csv, f.count, f.duration);
  return cmd_pub(bus, f.channel, f.type, f.assignments, f.rate, f.count);
}

}  // namespace lcm_control::tools
