#include "tools/lib/scenarios/scenario.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "bus/bus.hpp"
#include "description/robot_model.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "tools/lib/clients/trajectory_goal.hpp"
#include "tools/lib/launch/launch_file.hpp"
#include "tools/lib/launch/launcher.hpp"
#include "tools/lib/messages/message_json.hpp"

namespace fs = std::filesystem;

namespace lcm_control::tools {

const std::set<std::string>& scenario_keys() {
  static const std::set<std::string> keys = {"name", "launch", "launch_args", "duration", "requires",
                                             "timeline", "checks", "golden", "package_path"};
  return keys;
}

std::string scenario_name(const std::string& file) {
  std::string name = fs::path(file).stem().string();
  if (name.size() > 9 && name.compare(name.size() - 9, 9, ".scenario") == 0) name.resize(name.size() - 9);
  return name;
}

namespace {

// A YAML value as JSON, each scalar as its text (build_message reads numbers, booleans and names from text).
nlohmann::json to_json(const YAML::Node& n) {
  if (n.IsMap()) {
    nlohmann::json o = nlohmann::json::object();
    for (const auto& kv : n) o[kv.first.as<std::string>()] = to_json(kv.second);
    return o;
  }
  if (n.IsSequence()) {
    nlohmann::json a = nlohmann::json::array();
    for (const auto& e : n) a.push_back(to_json(e));
    return a;
  }
  if (n.IsScalar()) return n.as<std::string>();
  return nullptr;
}

class Reader {
 public:
  Reader(std::string path) : path_(std::move(path)) {}
  std::vector<std::string> problems;

  std::string where(const YAML::Node& n, const std::string& key) const {
    return fmt::format("{}:{}: {}", path_, n.Mark().line + 1, key);
  }
  void problem(const YAML::Node& n, const std::string& key, const std::string& what) {
    problems.push_back(fmt::format("{}: {}", where(n, key), what));
  }
  std::optional<double> number(const YAML::Node& n, const std::string& key) {
    try {
      const double v = n.as<double>();
      if (std::isfinite(v)) return v;
    } catch (const YAML::Exception&) {
    }
    problem(n, key, "must be a number");
    return std::nullopt;
  }
  std::string text(const YAML::Node& n, const std::string& key) {
    if (n.IsScalar()) return n.as<std::string>();
    problem(n, key, "must be a single value");
    return "";
  }
  std::vector<std::string> words(const YAML::Node& n, const std::string& key) {
    std::vector<std::string> out;
    if (n.IsScalar()) return {n.as<std::string>()};
    if (!n.IsSequence()) {
      problem(n, key, "must be a name or a list of names");
      return out;
    }
    for (const auto& e : n) out.push_back(text(e, key));
    return out;
  }
  std::vector<double> numbers(const YAML::Node& n, const std::string& key) {
    std::vector<double> out;
    if (n.IsScalar()) {
      if (auto v = number(n, key)) out.push_back(*v);
      return out;
    }
    if (!n.IsSequence()) {
      problem(n, key, "must be a number or a list of numbers");
      return out;
    }
    for (const auto& e : n)
      if (auto v = number(e, key)) out.push_back(*v);
    return out;
  }
  // The keys of a map, each checked against `valid`.
  bool keys(const YAML::Node& n, const std::string& key, const std::set<std::string>& valid) {
    if (!n.IsMap()) {
      problem(n, key, fmt::format("must be a map with {}", fmt::join(valid, ", ")));
      return false;
    }
    bool ok = true;
    for (const auto& kv : n)
      if (!valid.count(kv.first.as<std::string>())) {
        problem(kv.first, key + "." + kv.first.as<std::string>(),
                fmt::format("unknown key; valid: {}", fmt::join(valid, ", ")));
        ok = false;
      }
    return ok;
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

nlohmann::json vector3(Reader& r, const YAML::Node& n, const std::string& key) {
  const std::vector<double> v = r.numbers(n, key);
  if (v.size() == 1) return {{"x", v[0]}, {"y", 0.0}, {"z", 0.0}};
  if (v.size() == 3) return {{"x", v[0]}, {"y", v[1]}, {"z", v[2]}};
  r.problem(n, key, "must be a number (x) or [x, y, z]");
  return nlohmann::json::object();
}

// One timeline entry: `at` and one input.
void read_entry(Reader& r, const YAML::Node& e, size_t index, Scenario& s) {
  static const std::set<std::string> kinds = {"command", "goal", "gripper", "cmd_vel", "switch", "e_stop",
                                              "command_source", "publish", "wrench", "pause", "reset"};
  if (!r.keys(e, "timeline", [] {
        std::set<std::string> k = kinds;
        k.insert({"at", "every", "until"});
        return k;
      }()))
    return;
  TimelineEntry t;
  if (!e["at"]) r.problem(e, "timeline", "needs `at:` (seconds of sim time)");
  else if (auto at = r.number(e["at"], "at")) t.at = *at;
  if (t.at < 0) r.problem(e["at"], "at", "must be 0 or later");
  std::string kind;
  for (const auto& kv : e)
    if (kinds.count(kv.first.as<std::string>())) {
      if (!kind.empty()) r.problem(kv.first, "timeline", fmt::format("one input per entry: {} and {}", kind, kv.first.as<std::string>()));
      kind = kv.first.as<std::string>();
    }
  if (kind.empty()) {
    r.problem(e, "timeline", fmt::format("names no input; one of: {}", fmt::join(kinds, ", ")));
    return;
  }
  const YAML::Node v = e[kind];
  t.where = r.where(v, kind);
  auto controller = [&](const YAML::Node& m) {
    if (!m["controller"]) {
      r.problem(m, kind, "needs `controller:`");
      return std::string();
    }
    t.controller = r.text(m["controller"], kind + ".controller");
    return t.controller;
  };
  if (kind == "command") {
    if (!r.keys(v, kind, {"controller", "value", "values"})) return;
    t.channel = controller(v) + "/command";
    if (v["value"] && !v["values"]) {
      t.type = "float64_t";
      if (auto x = r.number(v["value"], "command.value")) t.fields = {{"data", *x}};
    } else if (v["values"] && !v["value"]) {
      t.type = "float64_array_t";
      t.fields = {{"data", r.numbers(v["values"], "command.values")}};
    } else {
      r.problem(v, kind, "needs `value: X` (a one-joint controller, float64_t) or `values: [...]` (a group, float64_array_t)");
    }
  } else if (kind == "goal") {
    if (!r.keys(v, kind, {"controller", "joint_names", "points"})) return;
    t.channel = controller(v) + "/command";
    t.type = "joint_trajectory_t";
    if (!v["joint_names"]) r.problem(v, kind, "needs `joint_names:` (the goal's joints, in its points' order)");
    YAML::Node goal = YAML::Clone(v);
    goal.remove("controller");
    try {
      TrajectoryGoal g = parse_goal_yaml(YAML::Dump(goal), r.path());
      check_goal(g);
      const joint_trajectory_t m = to_message(g, int64_t(1000 + index), 0);
      std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
      m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
      t.fields = message_to_json(bytes.data(), bytes.size());
    } catch (const ModelError& err) {
      for (const auto& p : err.problems()) r.problem(v, kind, p);
    } catch (const std::exception& err) {
      r.problem(v, kind, err.what());
    }
  } else if (kind == "gripper") {
    if (!r.keys(v, kind, {"controller", "position", "max_effort"})) return;
    t.channel = controller(v) + "/command";
    t.type = "gripper_command_t";
    if (!v["position"]) r.problem(v, kind, "needs `position:` (where the gripper joint goes, rad or m)");
    t.fields = {{"goal_id", int64_t(1000 + index)},
                {"position", v["position"] ? r.number(v["position"], "gripper.position").value_or(0) : 0.0},
                {"max_effort", v["max_effort"] ? r.number(v["max_effort"], "gripper.max_effort").value_or(0) : 0.0}};
  } else if (kind == "cmd_vel") {
    if (!r.keys(v, kind, {"controller", "linear", "angular", "channel"})) return;
    t.channel = controller(v) + "/cmd_vel";
    t.type = "twist_t";
    t.fields = {{"linear", v["linear"] ? vector3(r, v["linear"], "cmd_vel.linear") : vector3(r, YAML::Node(0), "")},
                {"angular", nlohmann::json{{"x", 0.0}, {"y", 0.0}, {"z", 0.0}}}};
    if (v["angular"]) {
      const std::vector<double> a = r.numbers(v["angular"], "cmd_vel.angular");
      if (a.size() == 1) t.fields["angular"]["z"] = a[0];  // turning about z: a base's
      else t.fields["angular"] = vector3(r, v["angular"], "cmd_vel.angular");
    }
  } else if (kind == "switch") {
    if (!r.keys(v, kind, {"start", "stop", "strictness"})) return;
    t.channel = channels::kCmRequest;
    t.type = "cm_request_t";
    const std::string strict = v["strictness"] ? r.text(v["strictness"], "switch.strictness") : "strict";
    if (strict != "strict" && strict != "best_effort") r.problem(v["strictness"], "switch.strictness", "strict or best_effort");
    t.fields = {{"request_id", int64_t(1000 + index)},
                {"client", "scenario"},
                {"op", int(cm_request_t::SWITCH)},
                {"start", v["start"] ? r.words(v["start"], "switch.start") : std::vector<std::string>{}},
                {"stop", v["stop"] ? r.words(v["stop"], "switch.stop") : std::vector<std::string>{}},
                {"strictness", int(strict == "strict" ? cm_request_t::STRICT : cm_request_t::BEST_EFFORT)}};
  } else if (kind == "e_stop") {
    t.channel = channels::kEStop;
    t.type = "e_stop_t";
    bool engaged = false;
    try {
      engaged = v.as<bool>();
    } catch (const YAML::Exception&) {
      r.problem(v, kind, "must be true (engage) or false (release)");
    }
    t.fields = {{"engaged", engaged}, {"source", "scenario"}};
  } else if (kind == "command_source") {
    if (!r.keys(v, kind, {"controller", "expr", "rate", "count", "duration", "remove"})) return;
    t.channel = channels::kCmCommandSource;
    t.type = "command_source_t";
    t.fields = {{"request_id", int64_t(1000 + index)}, {"client", "scenario"}, {"controller", controller(v)}};
    if (v["expr"]) t.fields["expressions"] = r.words(v["expr"], "command_source.expr");
    if (v["rate"]) t.fields["rate_hz"] = r.number(v["rate"], "command_source.rate").value_or(0);
    if (v["count"]) t.fields["count"] = int64_t(r.number(v["count"], "command_source.count").value_or(0));
    if (v["duration"]) t.fields["duration_s"] = r.number(v["duration"], "command_source.duration").value_or(0);
    if (v["remove"]) t.fields["remove"] = v["remove"].as<bool>(false);
    if (!v["expr"] && !v["remove"]) r.problem(v, kind, "needs `expr:` (muparser in i and t), or `remove: true`");
  } else if (kind == "publish") {
    if (!r.keys(v, kind, {"channel", "type", "message"})) return;
    if (!v["channel"] || !v["type"]) r.problem(v, kind, "needs `channel:` and `type:` (and `message:` with its fields)");
    t.channel = v["channel"] ? r.text(v["channel"], "publish.channel") : "";
    t.type = v["type"] ? r.text(v["type"], "publish.type") : "";
    t.fields = v["message"] ? to_json(v["message"]) : nlohmann::json::object();
  } else if (kind == "pause" || kind == "reset") {
    // sim_server's requests: a pause holds sim time for S seconds of the scenario's (a PAUSE, then a RESUME); a
    // reset puts every joint back at its start pose (`reset: {}`; `reset: {JOINT: POSITION}` moves that pose) and
    // sim time to 0.
    t.channel = channels::kSimRequest;
    t.type = "sim_request_t";
    t.fields = {{"request_id", int64_t(1000 + index)}, {"client", "scenario"}};
    if (kind == "reset") {
      t.fields["op"] = int(sim_request_t::RESET);
      std::vector<std::string> joints;
      std::vector<double> positions;
      if (!v.IsMap()) r.problem(v, kind, "must be {} or a map of JOINT: POSITION (the start pose's changes)");
      else
        for (const auto& kv : v) {
          joints.push_back(kv.first.as<std::string>());
          positions.push_back(r.number(kv.second, "reset." + joints.back()).value_or(0));
        }
      t.fields["joint"] = joints;
      t.fields["position"] = positions;
    } else {
      const double held = r.number(v, "pause").value_or(0);
      if (held <= 0) r.problem(v, kind, "must be the seconds (of the scenario's time) sim time holds, more than 0");
      t.fields["op"] = int(sim_request_t::PAUSE);
      TimelineEntry resume = t;
      resume.at = t.at + held;
      resume.fields["op"] = int(sim_request_t::RESUME);
      resume.fields["request_id"] = int64_t(100000 + index);
      s.timeline.push_back(std::move(resume));
    }
    s.pauses_or_resets = true;
  } else if (kind == "wrench") {
    if (!r.keys(v, kind, {"link", "force", "torque", "duration"})) return;
    t.channel = channels::kSimRequest;
    t.type = "sim_request_t";
    if (!v["link"] || !v["duration"]) r.problem(v, kind, "needs `link:` and `duration:` (s), and `force:` or `torque:`");
    t.fields = {{"request_id", int64_t(1000 + index)},
                {"client", "scenario"},
                {"op", int(sim_request_t::APPLY_WRENCH)},
                {"link", v["link"] ? r.text(v["link"], "wrench.link") : ""},
                {"force", v["force"] ? vector3(r, v["force"], "wrench.force") : vector3(r, YAML::Node(0), "")},
                {"torque", v["torque"] ? vector3(r, v["torque"], "wrench.torque") : vector3(r, YAML::Node(0), "")},
                {"duration", v["duration"] ? r.number(v["duration"], "wrench.duration").value_or(0) : 0.0}};
  }
  if (kind == "cmd_vel" && v["channel"]) t.channel = r.text(v["channel"], "cmd_vel.channel");
  if (t.fields.is_object()) t.fields.erase("utime");
  if (!t.type.empty() && r.problems.empty()) {
    try {
      message_from_json(t.type, t.fields, 0);  // what it would publish builds now, or is named now
    } catch (const std::exception& err) {
      r.problem(v, kind, err.what());
    }
  }
  // `every: S` with `until: T`: the same input again every S seconds up to T (a teleop's rate, a timeout fed).
  if (e["every"] || e["until"]) {
    const double every = e["every"] ? r.number(e["every"], "every").value_or(0) : 0;
    const double until = e["until"] ? r.number(e["until"], "until").value_or(-1) : -1;
    if (every <= 0 || until < t.at) {
      r.problem(e, "timeline", "`every: S` (seconds, > 0) goes with `until: T` (a sim time not before `at`)");
      return;
    }
    for (int64_t n = 0; t.at + double(n) * every <= until + 1e-9; ++n) {
      TimelineEntry copy = t;
      copy.at = t.at + double(n) * every;
      s.timeline.push_back(std::move(copy));
    }
    return;
  }
  s.timeline.push_back(std::move(t));
}

void read_check(Reader& r, const YAML::Node& c, Scenario& s) {
  static const std::set<std::string> valid = {"name",      "at",     "window",    "by",        "channel", "field",
                                              "near",      "tolerance", "min",   "max",       "tracking", "command",
                                              "rms_below", "max_below", "goal",  "result",    "odometry", "within",
                                              "within_yaw", "command_field"};
  if (!r.keys(c, "checks", valid)) return;
  Check k;
  k.where = r.where(c, "check");
  auto num = [&](const char* key) -> std::optional<double> {
    return c[key] ? r.number(c[key], key) : std::nullopt;
  };
  if (c["at"]) k.from = k.to = num("at").value_or(-1);
  if (c["by"]) k.to = num("by").value_or(-1);
  if (c["window"]) {
    const std::vector<double> w = r.numbers(c["window"], "window");
    if (w.size() != 2 || w[0] > w[1]) r.problem(c["window"], "window", "must be [from, to] in seconds of sim time");
    else k.from = w[0], k.to = w[1];
  }
  if (int(bool(c["at"])) + int(bool(c["window"])) + int(bool(c["by"])) > 1)
    r.problem(c, "check", "one of `at:`, `window:` or `by:`");
  std::string when = k.from < 0 && k.to < 0 ? "at the end"
                     : k.from == k.to     ? fmt::format("at t={:g} s", k.to)
                     : k.from < 0         ? fmt::format("by t={:g} s", k.to)
                                          : fmt::format("over [{:g}, {:g}] s", k.from, k.to);
  if (c["channel"] && !c["field"] && !c["odometry"])
    r.problem(c, "check", "`channel:` goes with `field:` (or names an `odometry:` controller's own channel)");
  const int kinds = int(bool(c["field"])) + int(bool(c["tracking"])) + int(bool(c["goal"])) + int(bool(c["odometry"]));
  if (kinds != 1) {
    r.problem(c, "check", "names one thing to check: `channel:` with `field:`, `tracking: JOINT`, `goal: CONTROLLER` or "
                          "`odometry: CONTROLLER`");
    return;
  }
  if (c["field"]) {
    k.kind = Check::Kind::Value;
    k.channel = c["channel"] ? r.text(c["channel"], "channel") : channels::kJointStates;
    k.field = r.text(c["field"], "field");
    k.near = num("near");
    k.tolerance = num("tolerance");
    k.min = num("min");
    k.max = num("max");
    if (k.near.has_value() != k.tolerance.has_value())
      r.problem(c, "check", "`near:` goes with `tolerance:`");
    if (!k.near && !k.min && !k.max) r.problem(c, "check", "needs `near:` with `tolerance:`, or `min:` and/or `max:`");
    k.name = fmt::format("{} {} {}", k.channel, k.field, when);
  } else if (c["tracking"]) {
    k.kind = Check::Kind::Tracking;
    k.joint = r.text(c["tracking"], "tracking");
    k.channel = c["command"] ? r.text(c["command"], "command") : "";
    if (c["command_field"]) k.command_field = r.text(c["command_field"], "command_field");
    if (k.channel.empty()) r.problem(c, "check", "tracking needs `command:` (the channel of the joint's command)");
    k.rms_below = num("rms_below");
    k.max_below = num("max_below");
    if (!k.rms_below && !k.max_below) r.problem(c, "check", "tracking needs `rms_below:` and/or `max_below:`");
    k.name = fmt::format("tracking {} {}", k.joint, when);
  } else if (c["goal"]) {
    k.kind = Check::Kind::Goal;
    k.controller = r.text(c["goal"], "goal");
    k.channel = k.controller + "/result";
    k.result = c["result"] ? r.text(c["result"], "result") : "SUCCEEDED";
    static const std::set<std::string> results = {"ACTIVE", "SUCCEEDED", "REJECTED", "PATH_TOLERANCE_VIOLATED",
                                                  "GOAL_TOLERANCE_VIOLATED", "PREEMPTED", "ABORTED"};
    if (!results.count(k.result))
      r.problem(c["result"], "result", fmt::format("'{}' is no result; one of {}", k.result, fmt::join(results, ", ")));
    k.name = fmt::format("goal of {} {} {}", r.text(c["goal"], "goal"), k.result, when);
  } else {
    k.kind = Check::Kind::Odometry;
    k.channel = c["channel"] ? r.text(c["channel"], "channel") : r.text(c["odometry"], "odometry") + "/odom";
    k.within_m = num("within").value_or(0);
    k.within_rad = num("within_yaw").value_or(0);
    if (!c["within"]) r.problem(c, "check", "odometry needs `within:` (m of ground truth; `within_yaw:` rad)");
    k.name = fmt::format("odometry of {} {}", r.text(c["odometry"], "odometry"), when);
  }
  if (c["name"]) k.name = r.text(c["name"], "name");
  s.checks.push_back(std::move(k));
}

}  // namespace

Scenario read_scenario(const std::string& path, const std::vector<std::string>& package_path) {
  const YAML::Node root = read_yaml_map(path, "launch keys, duration, timeline and checks");
  Reader r(path);
  Scenario s;
  s.file = path;
  s.name = root["name"] ? r.text(root["name"], "name") : scenario_name(path);
  const std::string dir = fs::absolute(path).parent_path().string();
  if (root["requires"])
    for (const std::string& f : r.words(root["requires"], "requires")) s.requires_files.push_back(absolute_from(f, dir));
  for (const auto& f : s.requires_files)
    if (!fs::exists(f)) return s;  // skipped: its robot is not in this checkout; nothing else is read
  if (!root["duration"]) r.problem(root, "duration", "is required: seconds of sim time the scenario runs");
  else s.duration = r.number(root["duration"], "duration").value_or(0);
  if (root["duration"] && s.duration <= 0) r.problem(root["duration"], "duration", "must be more than 0");
  if (root["golden"]) s.golden = absolute_from(r.text(root["golden"], "golden"), dir);
  if (root["package_path"])
    for (const std::string& d : r.words(root["package_path"], "package_path")) s.package_path.push_back(absolute_from(d, dir));
  LaunchOptions o;
  o.package_path = s.package_path;
  o.package_path.insert(o.package_path.end(), package_path.begin(), package_path.end());
  o.mode = "lockstep";
  o.cpu = "none";
  if (root["launch"]) {
    o.file = absolute_from(r.text(root["launch"], "launch"), dir);
    for (const auto& kv : root)
      if (!scenario_keys().count(kv.first.as<std::string>()))
        r.problem(kv.first, kv.first.as<std::string>(), "a scenario with `launch: FILE` takes its robot from that file: "
                                                        "put launch keys there, or drop `launch:` and write them here");
    if (root["launch_args"] && !root["launch_args"].IsMap())
      r.problem(root["launch_args"], "launch_args", "must be a map of NAME: VALUE (the launch file's <arg>s)");
    else if (root["launch_args"])
      for (const auto& kv : root["launch_args"])
        if (kv.second.IsScalar()) o.args.push_back(kv.first.as<std::string>() + "=" + kv.second.as<std::string>());
        else r.problem(kv.second, "launch_args." + kv.first.as<std::string>(), "must be a single value");
  } else {
    o.file = path;
    o.embedding_keys = scenario_keys();
    if (root["launch_args"])
      r.problem(root["launch_args"], "launch_args", "goes with `launch: FILE`; here the launch keys are in this file "
                                                    "(`args:` for the YAML's $(arg)s, `xacro_args:` for the robot's)");
  }
  if (root["timeline"]) {
    if (!root["timeline"].IsSequence()) r.problem(root["timeline"], "timeline", "must be a list of {at: T, INPUT: ...}");
    else
      for (size_t k = 0; k < root["timeline"].size(); ++k) read_entry(r, root["timeline"][k], k, s);
  }
  if (!root["checks"] || !root["checks"].IsSequence() || root["checks"].size() == 0)
    r.problem(root, "checks", "needs at least one check: a scenario that checks nothing cannot fail");
  else
    for (const auto& c : root["checks"]) read_check(r, c, s);
  if (s.pauses_or_resets && !s.golden.empty())
    r.problems.push_back(fmt::format("{}: golden: a scenario that pauses or resets the simulation has no golden log yet "
                                     "(replay --sim does not serve sim_server's requests); leave `golden:` out",
                                     path));
  for (const Check& c : s.checks)
    if (std::max(c.from, c.to) > s.duration + 1e-9)
      r.problems.push_back(fmt::format("{}: t={:g} s is after the scenario's end ({:g} s)", c.where,
                                       std::max(c.from, c.to), s.duration));
  for (const auto& t : s.timeline)
    if (t.at > s.duration) r.problems.push_back(fmt::format("{}: at {:g} s is after the scenario's end ({:g} s)", t.where, t.at, s.duration));
  if (!r.problems.empty()) throw ModelError(r.problems);
  try {
    s.launch = resolve_launch(o);
  } catch (const CLI::Error& e) {
    throw ModelError(fmt::format("{}: {}", path, e.what()));
  }
  if (!s.launch.robots.empty()) throw ModelError(fmt::format("{}: a scenario runs one robot, not `robots:`", path));
  s.launch.mode = "lockstep";
  s.launch.cpu = "none";
  std::stable_sort(s.timeline.begin(), s.timeline.end(),
                   [](const TimelineEntry& a, const TimelineEntry& b) { return a.at < b.at; });
  // Every request and goal its own id, in time order (a repeated one would be answered again, not done again).
  for (size_t k = 0; k < s.timeline.size(); ++k)
    for (const char* id : {"request_id", "goal_id"})
      if (s.timeline[k].fields.is_object() && s.timeline[k].fields.contains(id))
        s.timeline[k].fields[id] = int64_t(1000 + k);
  return s;
}

}  // namespace lcm_control::tools
