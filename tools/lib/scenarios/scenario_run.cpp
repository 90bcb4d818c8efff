#include "tools/lib/scenarios/scenario_run.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <chrono>
#include <cstring>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>

#include "bus/bus.hpp"
#include "bus/messages.hpp"
#include "bus/run_config.hpp"
#include "bus/digest.hpp"
#include "lcm_control/cm_inputs_t.hpp"
#include "controller_manager/input_stamps.hpp"
#include "controller_manager/program.hpp"
#include "description/load.hpp"
#include "description/text.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/controller_info_t.hpp"
#include "lcm_control/gripper_command_t.hpp"
#include "lcm_control/gripper_status_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/sim_response_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "tools/lib/clients/gripper_goal.hpp"
#include "tools/lib/clients/trajectory_goal.hpp"
#include "tools/lib/launch/launcher.hpp"
#include "tools/lib/logs/closed_loop.hpp"
#include "tools/lib/logs/replay.hpp"
#include "tools/lib/messages/fields.hpp"
#include "tools/lib/messages/message_json.hpp"
#include "tools/lib/scenarios/scenario.hpp"

namespace fs = std::filesystem;

namespace lcm_control::tools {

const char* outcome_name(ScenarioResult::Outcome o) {
  switch (o) {
    case ScenarioResult::Outcome::Passed: return "passed";
    case ScenarioResult::Outcome::Failed: return "FAILED";
    case ScenarioResult::Outcome::Skipped: return "skipped";
    case ScenarioResult::Outcome::Error: return "ERROR";
  }
  return "?";
}

namespace {

// Everything the bus carried, in order, each message at the scenario's time of the cycle it came in: its cycles
// since the start times the control period (sim time, but for what a pause holds and a reset sets back).
struct Recording {
  struct Event {
    int64_t t_us;
    std::string channel;
    std::vector<uint8_t> bytes;
  };
  std::vector<Event> events;
  int64_t now_us = 0;
  std::unique_ptr<lcm::LogFile> log;
  void on(const lcm::ReceiveBuffer* rb, const std::string& channel) {
    const auto* b = static_cast<const uint8_t*>(rb->data);
    events.push_back({now_us, channel, std::vector<uint8_t>(b, b + rb->data_size)});
    if (log) {
      lcm::LogEvent e{};
      e.eventnum = int64_t(events.size() - 1);
      e.timestamp = events.back().t_us;
      e.channel = channel;
      e.datalen = int32_t(rb->data_size);
      e.data = rb->data;
      log->writeEvent(&e);
    }
  }
};

template <class T>
std::optional<T> decoded(const Recording::Event& e) {
  T m;
  if (!decode_guarded(m, e.bytes.data(), e.bytes.size())) return std::nullopt;
  return m;
}

std::string seconds(int64_t us) { return fmt::format("t={:.3f} s", us * 1e-6); }

// The events of a check's time: its window; at a time, the last at or before it; else the last of the run.
std::vector<const Recording::Event*> in_time(const Recording& rec, const std::string& channel, const Check& c) {
  std::vector<const Recording::Event*> out;
  const bool window = c.from >= 0 && c.to > c.from;
  const double end = c.to >= 0 ? c.to + 1e-9 : INFINITY;
  for (const auto& e : rec.events) {
    if (e.channel != channel) continue;
    const double t = e.t_us * 1e-6;
    if (t > end) break;
    if (window && t < c.from - 1e-9) continue;
    if (!window) out.clear();
    out.push_back(&e);
  }
  return out;
}

// The one number `field` names in a message, or why not.
std::optional<double> field_value(const Recording::Event& e, const std::string& field, std::string* why) {
  const Decoded d = decode_fields(e.bytes.data(), e.bytes.size());
  if (!d.ok()) {
    *why = fmt::format("{} is not one of lcm_control's messages ({})", e.channel, d.skip_reason);
    return std::nullopt;
  }
  const auto picked = select_fields(d.fields, field);
  if (picked.size() != 1 || picked[0]->is_text) {
    *why = fmt::format("{} ({}) has {} '{}'; nearest: {}", e.channel, d.type, picked.empty() ? "no field" : "no one number",
                       field, fmt::join(nearest_fields(d.fields, field), ", "));
    return std::nullopt;
  }
  return picked[0]->integer ? double(picked[0]->exact) : picked[0]->value;
}

CheckResult check_value(const Recording& rec, const Bus& bus, const Check& c) {
  CheckResult r{c.name, c.where, false, ""};
  const auto events = in_time(rec, bus.channel(c.channel), c);
  if (events.empty()) {
    r.detail = fmt::format("no message on {} {}", bus.channel(c.channel), c.to >= 0 ? fmt::format("by t={:g} s", c.to) : "");
    return r;
  }
  auto wanted = [&] {
    if (c.near) return fmt::format("wanted {:g} ± {:g}", *c.near, *c.tolerance);
    return fmt::format("wanted within [{}, {}]", c.min ? fmt::format("{:g}", *c.min) : "-inf",
                       c.max ? fmt::format("{:g}", *c.max) : "inf");
  };
  double lo = INFINITY, hi = -INFINITY;
  for (const Recording::Event* e : events) {
    std::string why;
    const auto v = field_value(*e, c.field, &why);
    if (!v) {
      r.detail = why;
      return r;
    }
    lo = std::min(lo, *v);
    hi = std::max(hi, *v);
    const bool ok = !std::isnan(*v) && (!c.near || std::abs(*v - *c.near) <= *c.tolerance) && (!c.min || *v >= *c.min) &&
                    (!c.max || *v <= *c.max);
    if (!ok) {
      r.detail = fmt::format("{} = {:.6g} at {}, {}", c.field, *v, seconds(e->t_us), wanted());
      return r;
    }
  }
  r.passed = true;
  r.detail = events.size() == 1 ? fmt::format("{} = {:.6g} at {}", c.field, lo, seconds(events[0]->t_us))
                                : fmt::format("{} in [{:.6g}, {:.6g}] over {} messages", c.field, lo, hi, events.size());
  return r;
}

CheckResult check_tracking(const Recording& rec, const Bus& bus, const Check& c) {
  CheckResult r{c.name, c.where, false, ""};
  const std::string js = bus.channel(channels::kJointStates), cmd = bus.channel(c.channel);
  std::optional<double> command;
  double sum = 0, worst = 0;
  int64_t n = 0, worst_at = 0;
  const double from = c.from >= 0 ? c.from : 0, to = c.to >= 0 ? c.to : INFINITY;
  for (const auto& e : rec.events) {
    if (e.channel == cmd) {
      if (!c.command_field.empty()) {
        std::string why;
        const auto v = field_value(e, c.command_field, &why);
        if (!v) {
          r.detail = why;
          return r;
        }
        command = *v;
        continue;
      }
      const Decoded d = decode_fields(e.bytes.data(), e.bytes.size());
      for (const Field& f : d.fields)
        if (f.path != "utime" && !f.is_text && f.path != "size") {
          command = f.value;
          break;
        }
      continue;
    }
    const double t = e.t_us * 1e-6;
    if (e.channel != js || !command || t < from - 1e-9 || t > to + 1e-9) continue;
    const auto m = decoded<joint_state_t>(e);
    if (!m) continue;
    for (size_t k = 0; k < m->name.size() && k < m->position.size(); ++k)
      if (m->name[k] == c.joint) {
        const double err = m->position[k] - *command;
        sum += err * err;
        ++n;
        if (n == 1 || std::abs(err) > worst || std::isnan(err)) worst = std::abs(err), worst_at = e.t_us;
      }
  }
  if (n == 0) {
    r.detail = fmt::format("no joint_states position of '{}' with a command on {} before it in the window", c.joint, cmd);
    return r;
  }
  const double rms = std::sqrt(sum / double(n));
  r.detail = fmt::format("rms {:.4g}{}, max {:.4g} at {}{} ({} samples)", rms,
                         c.rms_below ? fmt::format(" (below {:g})", *c.rms_below) : "", worst, seconds(worst_at),
                         c.max_below ? fmt::format(" (below {:g})", *c.max_below) : "", n);
  r.passed = (!c.rms_below || rms < *c.rms_below) && (!c.max_below || worst < *c.max_below) && std::isfinite(rms);
  return r;
}


CheckResult check_goal(const Recording& rec, const Bus& bus, const Check& c) {
  CheckResult r{c.name, c.where, false, ""};
  // The last goal sent to the controller by the check's time, and that goal's last result.
  const std::string goals = bus.channel(c.controller + "/command"), results = bus.channel(c.channel);
  const double end = c.to >= 0 ? c.to + 1e-9 : INFINITY;
  std::optional<int64_t> sent;
  struct Result {
    int64_t goal_id = -1, t_us = 0;
    std::string status, message;
  };
  std::optional<Result> last;
  for (const auto& e : rec.events) {
    if (e.t_us * 1e-6 > end) break;
    if (e.channel == goals) {
      if (const auto t = decoded<joint_trajectory_t>(e)) sent = t->goal_id, last.reset();
      else if (const auto g = decoded<gripper_command_t>(e)) sent = g->goal_id, last.reset();
    } else if (e.channel == results) {
      if (const auto t = decoded<trajectory_status_t>(e))
        last = Result{t->goal_id, e.t_us, status_name(t->status), t->message};
      else if (const auto g = decoded<gripper_status_t>(e))
        last = Result{g->goal_id, e.t_us, gripper_status_name(g->status), g->message};
      if (last && sent && last->goal_id != *sent) last.reset();  // an earlier goal's
    }
  }
  const std::string by = c.to >= 0 ? fmt::format(" by t={:g} s", c.to) : "";
  if (!last) {
    r.passed = c.result == "ACTIVE" && sent.has_value();
    r.detail = sent ? fmt::format("goal {}: no result on {}{} (still ACTIVE)", *sent, results, by)
                    : fmt::format("no goal on {} and no result on {}{}", goals, results, by);
    return r;
  }
  r.passed = last->status == c.result;
  r.detail = fmt::format("goal {} {} at {}{}", last->goal_id, last->status, seconds(last->t_us),
                         last->message.empty() ? "" : ": " + last->message);
  return r;
}

CheckResult check_odometry(const Recording& rec, const Bus& bus, const Check& c) {
  CheckResult r{c.name, c.where, false, ""};
  const std::string odom = bus.channel(c.channel), truth = bus.channel(channels::kBasePose);
  std::optional<odometry_t> first_truth, last_truth, last_odom;
  int64_t odom_at = 0;
  const double end = c.to >= 0 ? c.to + 1e-9 : INFINITY;
  for (const auto& e : rec.events) {
    if (e.t_us * 1e-6 > end) break;
    if (e.channel == truth) {
      last_truth = decoded<odometry_t>(e);
    } else if (e.channel == odom) {
      if (!last_odom && last_truth) first_truth = last_truth;  // the odometry's frame starts where the base was
      last_odom = decoded<odometry_t>(e);
      odom_at = e.t_us;
    }
  }
  if (!last_odom || !last_truth || !first_truth) {
    r.detail = fmt::format("{} on {} and ground truth on {} (a free base's) are both needed", last_odom ? "" : "nothing",
                           odom, truth);
    return r;
  }
  double x = last_odom->position.x, y = last_odom->position.y, yaw = last_odom->yaw;
  if (last_odom->frame_id != "world") {  // dead reckoning from the start pose: into the world frame
    const double c0 = std::cos(first_truth->yaw), s0 = std::sin(first_truth->yaw);
    x = first_truth->position.x + c0 * last_odom->position.x - s0 * last_odom->position.y;
    y = first_truth->position.y + s0 * last_odom->position.x + c0 * last_odom->position.y;
    yaw = first_truth->yaw + last_odom->yaw;
  }
  const double d = std::hypot(x - last_truth->position.x, y - last_truth->position.y);
  const double dyaw = std::abs(std::remainder(yaw - last_truth->yaw, 2 * M_PI));
  r.passed = d <= c.within_m && (c.within_rad <= 0 || dyaw <= c.within_rad);
  r.detail = fmt::format("at {}: odometry ({:.4f}, {:.4f}, yaw {:.4f}) vs ground truth ({:.4f}, {:.4f}, yaw {:.4f}): "
                         "{:.4f} m{} apart, {:.4f} rad{}",
                         seconds(odom_at), x, y, yaw, last_truth->position.x, last_truth->position.y, last_truth->yaw, d,
                         fmt::format(" (within {:g})", c.within_m), dyaw,
                         c.within_rad > 0 ? fmt::format(" (within {:g})", c.within_rad) : "");
  return r;
}

// The inputs published since the last cycle, stamped as the controller manager program stamps what it takes in
// (cm_inputs_t, before the cycle that takes them): a recorded scenario replays closed loop with them at their cycles.
class StampedInputs {
 public:
  StampedInputs(ClosedLoop& loop)
      : loop_(loop), channel_(loop.bus().channel(channels::kCmInputs)), is_input_(loop.bus()) {}
  void publish(const std::string& channel, const void* data, size_t size) {
    if (is_input_(channel, data, size)) {  // what the controller manager takes in, as its program stamps it
      stamp_.channel.push_back(channel);
      stamp_.digest.push_back(int64_t(message_digest(data, size)));
      stamp_.size.push_back(int32_t(size));
    }
    loop_.bus().lcm().publish(channel, data, unsigned(size));
  }
  template <class T>
  void publish(const std::string& channel, const T& m) {
    std::vector<uint8_t> bytes(size_t(m.getEncodedSize()));
    m.encode(bytes.data(), 0, int(bytes.size()));
    publish(channel, bytes.data(), bytes.size());
  }
  // The stamp of what the next cycle takes in, then the cycle.
  const hardware_command_t& cycle() {
    if (!stamp_.channel.empty()) {
      stamp_.utime = loop_.simulation().time_us();
      stamp_.session = loop_.io().session();
      stamp_.step = loop_.step();
      stamp_.num_inputs = int32_t(stamp_.channel.size());
      loop_.bus().lcm().publish(channel_, &stamp_);
      stamp_ = {};
    }
    return loop_.cycle();
  }

 private:
  ClosedLoop& loop_;
  std::string channel_;
  cm::InputFilter is_input_;
  cm_inputs_t stamp_{};
};

// The answers to requests published on the bus: id -> (ok, message).
struct Answers {
  std::map<int64_t, std::pair<bool, std::string>> by_id;
  void cm(const lcm::ReceiveBuffer*, const std::string&, const cm_response_t* m) { by_id[m->request_id] = {m->ok, m->message}; }
  void sim(const lcm::ReceiveBuffer*, const std::string&, const sim_response_t* m) { by_id[m->request_id] = {m->ok, m->message}; }
};

ScenarioResult run(const Scenario& s, const ScenarioRunOptions& o, ScenarioResult result) {
  const CommandLines lines = command_lines(s.launch, LaunchOptions{}, "", false);
  std::vector<std::string> sim_argv = with_ns(lines.sim, s.launch.ns), cm_argv = with_ns(lines.cm, s.launch.ns);
  std::vector<std::string> package_path = s.package_path;
  package_path.insert(package_path.end(), o.package_path.begin(), o.package_path.end());
  for (const std::string& dir : package_path)  // launch hands it to its children in their environment
    for (auto* argv : {&sim_argv, &cm_argv}) argv->insert(argv->end(), {"--package-path", dir});
  const sim::ProgramFlags sim_flags = parse_sim_command_line(sim_argv);
  LoadOptions sim_load = load_options(sim_flags.robot.files, sim_flags.robot.bus);
  sim_load.config_from_plugin = true;
  const cm::ProgramFlags cm_flags = parse_manager_command_line(cm_argv);
  LoadOptions cm_load = load_options(cm_flags.robot.files, cm_flags.robot.bus);
  cm_load.config_from_plugin = true;
  cm::ManagerOptions manager_options;
  manager_options.command_line = cm_argv;
  const RobotModel model = load_robot_model(cm_flags.robot.files.urdf, cm_flags.robot.files.config, cm_load);
  {  // every input for a controller names one the YAML configures
    std::vector<std::string> configured, problems;
    for (const ControllerSpec& c : model.controllers) configured.push_back(c.name);
    for (const TimelineEntry& t : s.timeline)
      if (!t.controller.empty() && std::find(configured.begin(), configured.end(), t.controller) == configured.end()) {
        const std::string near = closest_name(t.controller, configured, 3);
        problems.push_back(fmt::format("{}: no controller '{}' in {}{}; configured: {}", t.where, t.controller,
                                       model.config_path, near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                       fmt::join(configured, ", ")));
      }
    if (!problems.empty()) throw ModelError(problems);
  }
  ClosedLoop loop(sim_flags, sim_load, model, manager_options);
  Bus& bus = loop.bus();
  Recording rec;
  if (!o.record_log.empty()) {
    rec.log = std::make_unique<lcm::LogFile>(o.record_log, "w");
    if (!rec.log->good()) throw std::runtime_error(fmt::format("cannot write the log {}: {}", o.record_log, std::strerror(errno)));
  }
  bus.lcm().subscribe(".*", &Recording::on, &rec);
  Answers answers;
  bus.lcm().subscribe(bus.channel(channels::kCmResponse), &Answers::cm, &answers);
  bus.lcm().subscribe(bus.channel(channels::kSimResponse), &Answers::sim, &answers);
  ReplayedManager& m = loop.manager();
  StampedInputs inputs_in(loop);

  // What the run was started with, as both programs publish it at start: the log replays on its own.
  if (const cm::Reply r = m.manager.publish_config(); !r.ok) throw std::runtime_error(r.message);
  run_config_t sim_config;
  if (const std::string why = read_run_config(loop.sim_model(), "sim_server", sim_argv, &sim_config); !why.empty())
    throw std::runtime_error(why);
  bus.lcm().publish(bus.channel(channels::kSimConfig), &sim_config);
  m.pump();

  // The controllers, as launch's spawner starts them: loaded, then started in one strict switch.
  int64_t next_id = 1;
  auto ask = [&](cm_request_t req) {
    req.request_id = next_id++;
    req.client = "scenario";
    req.num_names = int32_t(req.names.size());
    req.num_start = int32_t(req.start.size());
    req.num_stop = int32_t(req.stop.size());
    inputs_in.publish(bus.channel(channels::kCmRequest), req);
    return req.request_id;
  };
  // Runs cycles (the physics held by its brakes) until the request is answered; its answer, or throws.
  auto answered = [&](int64_t id, const std::string& what) {
    m.pump();
    for (int k = 0; k < 1000 && !answers.by_id.count(id); ++k) {
      inputs_in.cycle();
      loop.advance();
    }
    const auto it = answers.by_id.find(id);
    if (it == answers.by_id.end()) throw std::runtime_error(what + ": the controller manager did not answer");
    if (!it->second.first) throw std::runtime_error(fmt::format("{}: {}", what, it->second.second));
  };
  std::vector<std::string> load = s.launch.controllers;
  load.insert(load.end(), s.launch.inactive.begin(), s.launch.inactive.end());
  if (!load.empty()) {
    cm_request_t req{};
    req.op = cm_request_t::LOAD;
    req.names = load;
    answered(ask(req), fmt::format("loading {}", fmt::join(load, ", ")));
  }
  if (!s.launch.controllers.empty()) {
    cm_request_t req{};
    req.op = cm_request_t::SWITCH;
    req.start = s.launch.controllers;
    req.strictness = cm_request_t::STRICT;
    answered(ask(req), fmt::format("starting {}", fmt::join(s.launch.controllers, ", ")));
  }
  for (const CommandSpec& c : s.launch.commands) {
    command_source_t req{};
    req.request_id = next_id++;
    req.client = "scenario";
    req.controller = c.target;
    req.expressions = c.expr;
    req.num_expressions = int32_t(c.expr.size());
    req.rate_hz = c.rate;
    req.count = c.count;
    req.duration_s = c.duration;
    inputs_in.publish(bus.channel(channels::kCmCommandSource), req);
    answered(req.request_id, "the command source of " + c.target);
  }

  // The timeline, each input before the cycle of its sim time. The controllers' first cycle (re)starts them on the
  // first hardware state, which resets what a command gave them before it: an input due by then is handed over
  // after it, at the next cycle.
  const double period = loop.control_period_s();
  const int64_t start = loop.step();
  const int64_t end = std::max<int64_t>(start, std::llround(s.duration / period));
  std::map<int64_t, std::string> inputs;  // request id -> the timeline entry it came from
  std::map<int64_t, cm_request_t> switches;  // request id -> a switch the timeline asked for
  size_t next = 0;
  for (int64_t k = start; k <= end; ++k) {
    rec.now_us = std::llround(double(k) * period * 1e6);
    for (; k > start && next < s.timeline.size() && std::llround(s.timeline[next].at / period) <= k; ++next) {
      const TimelineEntry& t = s.timeline[next];
      const std::vector<uint8_t> bytes = message_from_json(t.type, t.fields, loop.simulation().time_us());
      cm_request_t request;
      if (t.channel == channels::kCmRequest && decode_guarded(request, bytes.data(), bytes.size()) &&
          request.op == cm_request_t::SWITCH)
        switches[request.request_id] = request;
      if (t.fields.contains("request_id")) inputs[std::stoll(t.fields["request_id"].is_string()
                                                                  ? t.fields["request_id"].get<std::string>()
                                                                  : std::to_string(t.fields["request_id"].get<int64_t>()))] = t.where;
      inputs_in.publish(bus.channel(t.channel), bytes.data(), bytes.size());
    }
    inputs_in.cycle();
    while (loop.io().has_request()) loop.io().answer(loop.serve(loop.io().take_request()));
    if (k == end) break;
    loop.advance();
  }
  m.pump();
  result.steps = end - start;
  result.sim_s = double(end) * period;
  result.messages = int64_t(rec.events.size());
  rec.log.reset();

  for (const auto& [id, where] : inputs) {  // an input refused is a failure of the scenario, where it is written
    const auto it = answers.by_id.find(id);
    CheckResult c{"input accepted", where, it != answers.by_id.end() && it->second.first, ""};
    c.detail = it == answers.by_id.end() ? "not answered by the end" : it->second.second;
    if (!c.passed) result.checks.push_back(c);
  }
  {  // no controller error: what was started, and not stopped by the timeline, still runs at the end
    std::set<std::string> expected(s.launch.controllers.begin(), s.launch.controllers.end());
    for (const auto& [id, sent] : switches) {  // those the controller manager carried out (ids run in time order)
      const auto answer = answers.by_id.find(id);
      if (answer == answers.by_id.end() || !answer->second.first) continue;
      for (const auto& n : sent.stop) expected.erase(n);
      for (const auto& n : sent.start) expected.insert(n);
    }
    CheckResult c{"every controller started still running", s.file, true, ""};
    std::vector<std::string> not_running;
    for (const controller_info_t& i : m.manager.list())
      if (expected.count(i.name) && i.state != "running") not_running.push_back(fmt::format("{} is {}", i.name, i.state));
    c.passed = not_running.empty();
    c.detail = c.passed ? fmt::format("{} controller(s) running at the end", expected.size())
                        : fmt::format("at the end {}", fmt::join(not_running, ", "));
    result.checks.push_back(c);
  }
  for (const Check& c : s.checks) {
    switch (c.kind) {
      case Check::Kind::Value: result.checks.push_back(check_value(rec, bus, c)); break;
      case Check::Kind::Tracking: result.checks.push_back(check_tracking(rec, bus, c)); break;
      case Check::Kind::Goal: result.checks.push_back(check_goal(rec, bus, c)); break;
      case Check::Kind::Odometry: result.checks.push_back(check_odometry(rec, bus, c)); break;
    }
  }
  return result;
}

}  // namespace

ScenarioResult run_scenario(const std::string& file, const ScenarioRunOptions& o) {
  const auto wall0 = std::chrono::steady_clock::now();
  ScenarioResult result;
  result.file = file;
  result.name = scenario_name(file);
  try {
    const Scenario s = read_scenario(file, o.package_path);
    result.name = s.name;
    for (const auto& f : s.requires_files)
      if (!fs::exists(f)) {
        result.outcome = ScenarioResult::Outcome::Skipped;
        result.why = "needs " + f;
        return result;
      }
    result = run(s, o, result);
    if (o.golden && !s.golden.empty() && o.record_log.empty()) {
      CheckResult g{"replays its golden log", s.golden, false, ""};
      if (!fs::exists(s.golden)) {
        g.detail = fmt::format("no golden log {}: record it with `scenario record {}`", s.golden, file);
      } else {
        ReplayOptions ro;
        ro.log = s.golden;
        ro.urdf = s.launch.urdf;
        ro.configs = s.launch.configs;
        ro.load.ns = s.launch.ns;
        const ReplayReport rr = replay_closed_loop(ro);
        g.passed = rr.within_tolerance();
        std::string text = replay_report_text(rr, 0);
        g.detail = text.substr(text.find(rr.first ? "diverged" : "identical"));
        g.detail = g.detail.substr(0, g.detail.find('\n'));
      }
      result.checks.push_back(g);
    }
    bool passed = true;
    for (const auto& c : result.checks) passed = passed && c.passed;
    result.outcome = passed ? ScenarioResult::Outcome::Passed : ScenarioResult::Outcome::Failed;
  } catch (const ModelError& e) {
    result.outcome = ScenarioResult::Outcome::Error;
    result.why = fmt::format("{}", fmt::join(e.problems(), "\n"));
  } catch (const CLI::Error& e) {
    result.outcome = ScenarioResult::Outcome::Error;
    result.why = fmt::format("{}: {}", file, e.what());
  } catch (const std::exception& e) {
    result.outcome = ScenarioResult::Outcome::Error;
    result.why = fmt::format("{}: {}", file, e.what());
  }
  result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  return result;
}

}  // namespace lcm_control::tools
