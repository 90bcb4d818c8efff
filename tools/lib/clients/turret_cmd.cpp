#include "tools/lib/clients/turret_cmd.hpp"

#include <fmt/ranges.h>

#include <cmath>
#include <memory>
#include <optional>

#include "control/expression.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"
#include "tools/lib/clients/time_base.hpp"

namespace lcm_control::tools {
namespace {


// TARGET as given, without ROS's leading '/'.
std::string clean_target(const std::string& target) {
  const std::string t = without_leading_slashes(target);
  if (t.empty()) throw std::runtime_error("TARGET is empty: give a controller name or a channel");
  return t;
}
bool is_channel(const TurretCmdFlags& o) { return o.raw_channel || clean_target(o.target).find('/') != std::string::npos; }

// The controller TARGET commands: its name, or NAME of a channel TARGET "NAME/command"; "" for any other channel.
std::string controller_of(const TurretCmdFlags& o) {
  const std::string t = clean_target(o.target), suffix = "/command";
  if (!is_channel(o)) return t;
  if (t.size() <= suffix.size() || t.compare(t.size() - suffix.size(), suffix.size(), suffix) != 0) return "";
  const std::string name = t.substr(0, t.size() - suffix.size());
  return name.find('/') == std::string::npos ? name : "";
}

// Refuses (std::runtime_error, exit 1) commands of a type the controller does not take, when the controller manager
// lists it; says on stderr when nothing will take them: no controller manager answers in this namespace, the
// controller is not running in it, or the manager has no hardware. Those are sent regardless (a manager may come
// later), as rostopic pub does.
void say_who_takes(Bus& bus, const std::string& controller, const Sent& sent) {
  CmClient cm(bus, "turret-cmd");
  const std::string channel = bus.channel(controller + "/command");
  cm_response_t r;
  try {
    r = cm.list(0.5);
  } catch (const CmTimeout& e) {
    fmt::print(stderr,
               "turret-cmd: warning: no controller manager answers on '{}': nothing takes the commands on '{}' until "
               "one runs (launch, or controller_manager and spawner; --namespace and --lcm-url must match){}\n",
               cm.response_channel(), channel, e.hint.empty() ? "" : "; " + e.hint);
    return;
  }
  std::vector<std::string> loaded;
  const controller_info_t* found = nullptr;
  for (const auto& c : r.controllers) {
    loaded.push_back(c.name);
    if (c.name == controller) found = &c;
  }
  if (found)
    if (const std::string bad = type_mismatch(*found, sent, "command", bus.channel("")); !bad.empty())
      throw std::runtime_error(bad);
  if (!found)
    fmt::print(stderr,
               "turret-cmd: warning: '{}' is not loaded in the controller manager (loaded: {}): nothing takes the "
               "commands on '{}' until `spawner {}` starts it\n",
               controller, loaded.empty() ? "none" : fmt::format("{}", fmt::join(loaded, ", ")), channel, controller);
  else if (found->state != "running")
    fmt::print(stderr,
               "turret-cmd: warning: '{}' is {}, not running: it ignores the commands on '{}' until `cmctl start {}`\n",
               controller, found->state, channel, controller);
  if (r.hardware_age_us < 0)
    fmt::print(stderr, "turret-cmd: warning: the controller manager reports {}\n", r.hardware);
}

class Publisher {
 public:
  Publisher(Bus& bus, const TurretCmdFlags& o)
      : bus_(bus), o_(o), exprs_(o.exprs), array_(o.array || o.exprs.size() > 1), values_(o.exprs.size()) {
    const std::string t = clean_target(o.target);
    channel_ = is_channel(o) ? t : t + "/command";
  }
  const std::string& channel() const { return channel_; }
  const char* type() const { return array_ ? "float64_array_t" : "float64_t"; }
  Sent what() const { return {type(), array_ ? int(o_.exprs.size()) : 0}; }
  int64_t sent() const { return sent_; }

  void send(int64_t i, double t, int64_t utime) {
    exprs_.eval_checked(i, t, values_.data());
    const std::vector<double>& v = values_;
    if (array_) {
      float64_array_t m;
      m.utime = utime;
      m.size = int32_t(v.size());
      m.data = v;
      bus_.publish(channel_, m);
    } else {
      float64_t m;
      m.utime = utime;
      m.data = v[0];
      bus_.publish(channel_, m);
    }
    ++sent_;
    if (o_.print) fmt::print("{} {:.6f} {}\n", i, t, fmt::join(v, " "));
  }

 private:
  Bus& bus_;
  const TurretCmdFlags& o_;
  Expressions exprs_;
  bool array_;
  std::vector<double> values_;
  std::string channel_;
  int64_t sent_ = 0;
};

bool more(const TurretCmdFlags& o, int64_t i, double t) {
  if (o.count > 0 && i >= o.count) return false;
  if (o.duration > 0 && t >= o.duration) return false;
  return true;
}

// Wall clock: message i is due at start + i/rate on the monotonic clock. When the
// process falls more than one period behind, it re-anchors instead of bursting.
// Messages are stamped by `clock` (sim time when sim_server is on the bus).
int run_wall(Bus& bus, Publisher& pub, const TurretCmdFlags& o, const CommandClock& clock) {
  const int64_t start = monotonic_us();
  if (o.rate <= 0) {
    pub.send(0, 0.0, clock.now_us());
    return kExitOk;
  }
  const double period_us = 1e6 / o.rate;
  int64_t anchor = start, anchor_i = 0, late = 0;
  for (int64_t i = 0; !stop_requested(); ++i) {
    int64_t due = anchor + std::llround(double(i - anchor_i) * period_us);
    const double t = double(due - start) / 1e6;
    if (!more(o, i, t)) break;
    pump_until(bus, [] { return false; }, double(due - monotonic_us() - 1000) * 1e-6);  // sim time moves on
    sleep_until_us(due);
    if (stop_requested()) break;
    const int64_t now = monotonic_us();
    if (now - due > int64_t(period_us)) {
      anchor = due = now;
      anchor_i = i;
      ++late;
    }
    pub.send(i, double(due - start) / 1e6, clock.now_us());
  }
  if (late) fmt::print(stderr, "turret-cmd: fell behind the {:g} Hz schedule {} times\n", o.rate, late);
  return kExitOk;
}

// Sim time: paced by hardware/state, which sim_server publishes every control
// step (`clock` may come only every few steps). Message j is due at sim time
// j/rate (or at every control step without --rate). On the state of step k it
// sends every message due up to step k+1, so in lockstep the command for a step
// is normally on the bus before the controller manager reads that step. The
// control period comes from the state (utime / step), so on a first state of
// step 0 only message 0 goes out.
class SimTimePacer {
 public:
  SimTimePacer(Bus& bus, Publisher& pub, const TurretCmdFlags& o) : pub_(pub), o_(o) {
    subscribe_guarded<&SimTimePacer::on_state>(bus, bus.channel(channels::kHardwareState), this, Bus::On::Hardware);
  }
  bool done() const { return done_; }
  bool started() const { return started_; }
  int64_t last_state_us() const { return last_state_mono_; }
  int64_t sim_us() const { return last_utime_; }
  const std::string& error() const { return error_; }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const hardware_state_t* m) {
    if (done_) return;
    last_state_mono_ = monotonic_us();
    if (m->step > 0 && m->utime > 0) tick_us_ = double(m->utime) / double(m->step);
    if (!started_ || m->utime < last_utime_) {
      if (started_) fmt::print(stderr, "turret-cmd: sim time went back ({} -> {} us): restarting at i=0\n",
                               last_utime_, m->utime);
      started_ = true;
      start_us_ = m->utime;
      next_ = 0;
    }
    last_utime_ = m->utime;
    const double msg_period = o_.rate > 0 ? 1e6 / o_.rate : tick_us_;
    const double horizon = double(m->utime - start_us_) + tick_us_;
    if (msg_period <= 0) {
      if (next_ == 0) publish(0, 0.0);
      return;
    }
    const int64_t last = int64_t(std::floor(horizon / msg_period + 1e-9));
    for (int64_t j = next_; j <= last && !done_; ++j) {
      const double t = double(j) * msg_period / 1e6;
      if (o_.duration > 0 && double(j) * msg_period >= o_.duration * 1e6 - 0.5) {
        done_ = true;
        return;
      }
      publish(j, t);
    }
  }
  void publish(int64_t j, double t) {
    try {
      pub_.send(j, t, start_us_ + std::llround(t * 1e6));
    } catch (const std::exception& e) {
      error_ = e.what();
      done_ = true;
    }
    next_ = j + 1;
    if (o_.count > 0 && next_ >= o_.count) done_ = true;
  }

  Publisher& pub_;
  const TurretCmdFlags& o_;
  bool started_ = false, done_ = false;
  int64_t start_us_ = 0, last_utime_ = 0, next_ = 0, last_state_mono_ = 0;
  double tick_us_ = 0;
  std::string error_;
};

int run_sim_time(Bus& bus, Publisher& pub, const TurretCmdFlags& o) {
  SimTimePacer pacer(bus, pub, o);
  const int64_t begin = monotonic_us();
  const int64_t timeout_us = int64_t(o.timeout * 1e6);
  while (!pacer.done() && !stop_requested()) {
    handle_bus(bus, 50);
    const int64_t since = monotonic_us() - (pacer.started() ? pacer.last_state_us() : begin);
    if (since > timeout_us) {
      if (!pacer.started())
        throw std::runtime_error(fmt::format(
            "no hardware_state_t on '{}' ({}) for {}: is sim_server running on this --lcm-url/--namespace, with this "
            "--hardware-url?",
            bus.channel(channels::kHardwareState), bus.hardware_url(), seconds_text(o.timeout)));
      throw std::runtime_error(fmt::format(
          "sim time on '{}' stopped at {:.6f} s for {} after {} messages (sim_server paused or gone?)",
          bus.channel(channels::kHardwareState), double(pacer.sim_us()) * 1e-6, seconds_text(o.timeout), pub.sent()));
    }
  }
  if (!pacer.error().empty()) throw std::runtime_error(pacer.error());
  return kExitOk;
}

// Sim time with a controller TARGET: the controller manager generates the
// commands on hardware time (exact under lockstep: tick i is used at the step it
// is due). Waits for its answer, then until the source ends (or Ctrl-C, then
// removes it); --print shows the commands it publishes.
class SourceWatcher {
 public:
  SourceWatcher(Bus& bus, const TurretCmdFlags& o, const std::string& channel) : o_(o) {
    if (o.print) bus.subscribe(channel, &SourceWatcher::on_command, this);
  }
  int64_t seen() const { return seen_; }

 private:
  void on_command(const lcm::ReceiveBuffer* rb, const std::string&) {
    float64_array_t& many = many_;
    float64_t& one = one_;
    if (o_.exprs.size() > 1 && decode_guarded(many, rb->data, rb->data_size))
      fmt::print("{} {:.6f} {}\n", seen_, double(many.utime) * 1e-6, fmt::join(many.data, " "));
    else if (o_.exprs.size() == 1 && decode_guarded(one, rb->data, rb->data_size))
      fmt::print("{} {:.6f} {}\n", seen_, double(one.utime) * 1e-6, one.data);
    std::fflush(stdout);
    ++seen_;
  }
  const TurretCmdFlags& o_;
  int64_t seen_ = 0;
  float64_array_t many_{};
  float64_t one_{};
};

int run_command_source(Bus& bus, const TurretCmdFlags& o) {
  const std::string controller = clean_target(o.target);
  Expressions check(o.exprs);  // a bad expression fails here, naming it
  CmClient cm(bus, "turret-cmd");
  SourceWatcher watch(bus, o, bus.channel(controller + "/command"));
  command_source_t req{};
  req.controller = controller;
  req.expressions = o.exprs;
  req.rate_hz = o.rate;
  req.count = o.count;
  req.duration_s = o.duration;
  const cm_response_t answer = cm.command_source(req, o.timeout);
  if (!answer.ok) throw std::runtime_error(answer.message);
  fmt::print(stderr, "turret-cmd: {}\n", answer.message);
  const int64_t id = answer.request_id;
  while (!stop_requested()) {
    if (auto end = cm.source_ended(id, 0.05)) {
      fmt::print(stderr, "turret-cmd: {}\n", end->message);
      if (!end->ok) throw std::runtime_error(end->message);
      return kExitOk;
    }
  }
  clear_stop();  // the bus waits below stop early while a stop is pending
  command_source_t rm{};
  rm.controller = controller;
  rm.remove = true;
  try {
    const cm_response_t r = cm.command_source(rm, 2.0);
    fmt::print(stderr, "turret-cmd: {}\n", r.message);
  } catch (const CmTimeout& e) {
    fmt::print(stderr, "turret-cmd: could not remove the command source: {}\n", e.what());
  }
  return kExitOk;
}

}  // namespace

void add_turret_cmd_flags(CLI::App& app, TurretCmdFlags& o) {
  app.add_option("TARGET", o.target, "controller name, or a channel (contains '/', or with --as-channel)")->required();
  app.add_option("EXPR", o.exprs, "expression(s) in i and t, one per joint")->required();
  app.add_option("--rate", o.rate, "messages per second (default: publish once; with --sim-time: every control step)")
      ->check(CLI::PositiveNumber);
  app.add_option("--count", o.count, "stop after N messages")->check(CLI::PositiveNumber);
  app.add_option("--duration", o.duration, "stop after S seconds (sim seconds with --sim-time)")
      ->check(CLI::PositiveNumber);
  app.add_flag("--as-channel", o.raw_channel, "TARGET is a channel name, used as given");
  app.add_flag("--channel", o.raw_channel)->group("");  // --as-channel's old name, kept for scripts
  app.add_flag("--array", o.array, "send float64_array_t even for one EXPR");
  app.add_flag("--sim-time", o.sim_time,
               "sim time instead of the wall clock: a controller TARGET gets a command source in the controller manager "
               "(exact, deterministic under lockstep); a channel TARGET is paced by hardware/state (best effort)");
  app.add_option("--timeout", o.timeout,
                 "with --sim-time: seconds to wait for the controller manager's answer (controller TARGET) or for sim "
                 "time on hardware/state (channel TARGET)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_flag("--print", o.print, "print `i t value...` for every message sent");
  add_bus_flags(app, o.bus);
  add_hardware_url_flag(app, o.bus);
}

int run_turret_cmd(const TurretCmdFlags& o) {
  if (o.count > 1 && o.rate <= 0 && !o.sim_time) throw std::runtime_error("--count needs --rate (or --sim-time)");
  if (o.duration > 0 && o.rate <= 0 && !o.sim_time)
    throw std::runtime_error("--duration needs --rate (or --sim-time)");
  install_stop_signals();
  Bus bus(o.bus.lcm_url, o.bus.ns, o.bus.hardware_lcm_url, HardwareReader::Direct);
  if (o.sim_time && !is_channel(o)) {
    if (o.array) throw std::runtime_error("--array does not apply with --sim-time and a controller TARGET (the "
                                          "controller manager sends what the controller takes)");
    return run_command_source(bus, o);
  }
  Publisher pub(bus, o);
  if (const std::string controller = controller_of(o); !controller.empty()) say_who_takes(bus, controller, pub.what());
  if (o.rate > 0 || o.sim_time)
    fmt::print(stderr, "turret-cmd: {} on '{}' {}{} (Ctrl-C to stop)\n", pub.type(), bus.channel(pub.channel()),
               o.rate > 0 ? fmt::format("at {:g} Hz", o.rate) : std::string("every control step"),
               o.sim_time ? " of sim time" : "");
  int rc = kExitOk;
  if (o.sim_time) {
    rc = run_sim_time(bus, pub, o);
  } else {
    const CommandClock clock(bus, 0.3);
    rc = run_wall(bus, pub, o, clock);
  }
  fmt::print(stderr, "turret-cmd: sent {} message{} on '{}'\n", pub.sent(), pub.sent() == 1 ? "" : "s",
             bus.channel(pub.channel()));
  return rc;
}

}  // namespace lcm_control::tools
