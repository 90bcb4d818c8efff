#include "tools/fields.hpp"

#include <fmt/format.h>

#include "common/bus.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/controller_info_t.hpp"
#include "lcm_control/controller_state_t.hpp"
#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "lcm_control/trajectory_point_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"

namespace lcm_control::tools {

std::string Field::text() const {
  if (is_text) return str;
  return integer ? std::to_string(exact) : fmt::format("{}", value);
}

namespace {

class Out {
 public:
  explicit Out(std::vector<Field>& f) : f_(f) {}
  void num(const std::string& path, double v) { f_.push_back(Field{path, v, 0, false, false, ""}); }
  void integer(const std::string& path, int64_t v) { f_.push_back(Field{path, double(v), v, true, false, ""}); }
  void text(const std::string& path, const std::string& s) { f_.push_back(Field{path, 0, 0, false, true, s}); }
  void texts(const std::string& path, const std::vector<std::string>& v) {
    for (size_t k = 0; k < v.size(); ++k) text(fmt::format("{}[{}]", path, k), v[k]);
  }
  template <class T>
  void nums(const std::string& path, const std::vector<T>& v) {
    for (size_t k = 0; k < v.size(); ++k) num(fmt::format("{}[{}]", path, k), double(v[k]));
  }
  template <class T>
  void ints(const std::string& path, const std::vector<T>& v) {
    for (size_t k = 0; k < v.size(); ++k) integer(fmt::format("{}[{}]", path, k), int64_t(v[k]));
  }
  void nums2(const std::string& path, const std::vector<std::vector<double>>& v) {
    for (size_t k = 0; k < v.size(); ++k) nums(fmt::format("{}[{}]", path, k), v[k]);
  }

 private:
  std::vector<Field>& f_;
};

void flatten(const float64_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.num("data", m.data);
}
void flatten(const float64_array_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.nums("data", m.data);
}
void flatten(const joint_state_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.nums("position", m.position);
  o.nums("velocity", m.velocity);
  o.nums("effort", m.effort);
  o.texts("name", m.name);
}
void flatten(const hardware_state_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("step", m.step);
  o.integer("session", m.session);
  o.integer("lockstep", m.lockstep);
  o.integer("period_us", m.period_us);
  o.integer("e_stop", m.e_stop);
  o.num("real_time_factor", m.real_time_factor);
  o.ints("mode", m.mode);
  o.nums("position", m.position);
  o.nums("velocity", m.velocity);
  o.nums("effort", m.effort);
  o.texts("name", m.name);
}
void flatten(const hardware_command_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("step", m.step);
  o.integer("session", m.session);
  o.ints("mode", m.mode);
  o.nums("command", m.command);
  o.texts("name", m.name);
}
void flatten(const controller_state_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.num("set_point", m.set_point);
  o.num("process_value", m.process_value);
  o.num("process_value_dot", m.process_value_dot);
  o.num("error", m.error);
  o.num("time_step", m.time_step);
  o.num("command", m.command);
  o.num("p", m.p);
  o.num("i", m.i);
  o.num("d", m.d);
  o.num("i_clamp", m.i_clamp);
  o.integer("antiwindup", m.antiwindup);
  o.text("controller", m.controller);
  o.text("joint", m.joint);
}
void flatten(const e_stop_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("engaged", m.engaged);
  o.text("source", m.source);
}
void flatten(const link_poses_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.nums2("position", m.position);
  o.nums2("orientation", m.orientation);
  o.texts("name", m.name);
}
void flatten(const loop_stats_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("cycles", m.cycles);
  o.num("period_mean_us", m.period_mean_us);
  o.num("period_min_us", m.period_min_us);
  o.num("period_max_us", m.period_max_us);
  o.num("period_jitter_us", m.period_jitter_us);
  o.integer("overruns", m.overruns);
  o.integer("missed", m.missed);
  o.integer("dropped", m.dropped);
  o.num("real_time_factor", m.real_time_factor);
  o.num("exec_mean_us", m.exec_mean_us);
  o.num("exec_max_us", m.exec_max_us);
  o.nums("item_exec_mean_us", m.item_exec_mean_us);
  o.nums("item_exec_max_us", m.item_exec_max_us);
  o.text("process", m.process);
  o.texts("item", m.item);
}
void flatten(const pid_gains_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("request_id", m.request_id);
  o.integer("query", m.query);
  o.integer("ok", m.ok);
  o.num("p", m.p);
  o.num("i", m.i);
  o.num("d", m.d);
  o.num("i_clamp_min", m.i_clamp_min);
  o.num("i_clamp_max", m.i_clamp_max);
  o.integer("antiwindup", m.antiwindup);
  o.text("owner", m.owner);
  o.text("joint", m.joint);
  o.text("message", m.message);
}
void flatten(const sim_clock_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("step", m.step);
  o.num("real_time_factor", m.real_time_factor);
}
void flatten(const trajectory_status_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("goal_id", m.goal_id);
  o.integer("status", m.status);
  o.nums("desired", m.desired);
  o.nums("actual", m.actual);
  o.nums("error", m.error);
  o.text("message", m.message);
  o.texts("joint_names", m.joint_names);
}
void flatten(const joint_trajectory_t& m, Out& o) {
  o.integer("utime", m.utime);
  o.integer("goal_id", m.goal_id);
  for (size_t k = 0; k < m.points.size(); ++k) {
    const auto& p = m.points[k];
    const std::string base = fmt::format("points[{}].", k);
    o.num(base + "time_from_start", p.time_from_start);
    o.nums(base + "positions", p.positions);
    o.nums(base + "velocities", p.velocities);
    o.nums(base + "accelerations", p.accelerations);
  }
  o.texts("joint_names", m.joint_names);
}

struct TypeEntry {
  int64_t hash;
  const char* name;
  Decoded (*decode)(const void*, size_t);
  const char* skip_reason;  // non-null: known type without signals
};

template <class Msg>
Decoded decode_as(const void* data, size_t size) {
  Decoded d;
  d.type = std::string("lcm_control.") + Msg::getTypeName();
  Msg m{};
  if (!decode_guarded(m, data, size)) {
    d.skip_reason = "malformed payload (decode failed)";
    return d;
  }
  Out o(d.fields);
  flatten(m, o);
  return d;
}

template <class Msg>
TypeEntry decoded() {
  return TypeEntry{Msg::getHash(), Msg::getTypeName(), &decode_as<Msg>, nullptr};
}
template <class Msg>
TypeEntry skipped(const char* why) {
  return TypeEntry{Msg::getHash(), Msg::getTypeName(), nullptr, why};
}

const std::vector<TypeEntry>& table() {
  static const std::vector<TypeEntry> t = {
      decoded<float64_t>(),
      decoded<float64_array_t>(),
      decoded<joint_state_t>(),
      decoded<hardware_state_t>(),
      decoded<hardware_command_t>(),
      decoded<controller_state_t>(),
      decoded<e_stop_t>(),
      decoded<link_poses_t>(),
      decoded<loop_stats_t>(),
      decoded<pid_gains_t>(),
      decoded<sim_clock_t>(),
      decoded<trajectory_status_t>(),
      decoded<joint_trajectory_t>(),
      skipped<cm_request_t>("controller-manager request: names and options, no signals (see cmctl)"),
      skipped<cm_response_t>("controller-manager answer: names and text, no signals (see cmctl list)"),
      skipped<controller_info_t>("controller description: names only, no numbers"),
      skipped<trajectory_point_t>("a part of joint_trajectory_t, not sent on its own"),
  };
  return t;
}

int64_t read_hash(const void* data) {
  const auto* b = static_cast<const uint8_t*>(data);
  uint64_t h = 0;
  for (int k = 0; k < 8; ++k) h = (h << 8) | b[k];
  return int64_t(h);
}

}  // namespace

Decoded decode_fields(const void* data, size_t size) {
  Decoded d;
  if (size < 8) {
    d.skip_reason = fmt::format("payload of {} bytes is too short for an LCM message", size);
    return d;
  }
  const int64_t hash = read_hash(data);
  for (const auto& e : table()) {
    if (e.hash != hash) continue;
    if (e.decode) return e.decode(data, size);
    d.type = std::string("lcm_control.") + e.name;
    d.skip_reason = e.skip_reason;
    return d;
  }
  d.skip_reason = fmt::format("not an lcm_control type (fingerprint 0x{:016x})", uint64_t(hash));
  return d;
}

std::vector<std::string> known_types() {
  std::vector<std::string> out;
  for (const auto& e : table())
    out.push_back(e.decode ? std::string(e.name) : fmt::format("{} (skipped: {})", e.name, e.skip_reason));
  return out;
}

std::string csv_file_name(const std::string& channel) {
  std::string s;
  for (char c : channel) s += c == '/' ? std::string("__") : std::string(1, c);
  while (!s.empty() && s[0] == '_') s.erase(0, 1);
  return (s.empty() ? std::string("channel") : s) + ".csv";
}

}  // namespace lcm_control::tools
