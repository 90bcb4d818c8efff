#include "tools/lib/clients/trajectory_goal.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "description/robot_model.hpp"
#include "description/text.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

namespace {

std::string count_of(size_t n, const char* what) { return fmt::format("{} {}{}", n, what, n == 1 ? "" : "s"); }

// A comma-separated list of numbers; problems name `what` (positions, velocities) and the value's place.
std::vector<double> number_list(const std::string& text, const std::string& where, const char* what,
                                std::vector<std::string>& problems) {
  std::vector<double> out;
  const std::vector<std::string> cells = split(text, ',');
  for (size_t k = 0; k < cells.size(); ++k) {
    double v = 0;
    if (trim(cells[k]).empty())
      problems.push_back(fmt::format("{}: value {} of the {} is empty; give one number per joint, separated by commas",
                                     where, k + 1, what));
    else if (!parse_double(cells[k], v))
      problems.push_back(
          fmt::format("{}: '{}' (value {} of the {}) is not a finite number", where, trim(cells[k]), k + 1, what));
    out.push_back(v);
  }
  return out;
}

std::string line_of(const std::string& path, const YAML::Node& n) {
  return fmt::format("{}:{}", path, n.Mark().line + 1);
}

void check_keys(const YAML::Node& map, const std::vector<std::string>& valid, const std::string& path,
                const std::string& what, std::vector<std::string>& problems) {
  for (const auto& kv : map) {
    const std::string key = kv.first.Scalar();
    if (std::find(valid.begin(), valid.end(), key) != valid.end()) continue;
    const std::string close = closest_name(key, valid, 3);
    problems.push_back(fmt::format("{}: unknown key '{}' in {} (valid keys: {}){}", line_of(path, kv.first), key, what,
                                   fmt::join(valid, ", "), close.empty() ? "" : "; did you mean '" + close + "'?"));
  }
}

std::vector<double> yaml_numbers(const YAML::Node& n, const std::string& where, const char* key,
                                 std::vector<std::string>& problems) {
  std::vector<double> out;
  if (!n.IsSequence()) {
    problems.push_back(fmt::format("{}: {} must be a list of numbers, one per joint, e.g. [0.1, 0.2]", where, key));
    return out;
  }
  for (size_t k = 0; k < n.size(); ++k) {
    double v = 0;
    if (!n[k].IsScalar() || !parse_double(n[k].Scalar(), v))
      problems.push_back(fmt::format("{}: {} value {} ('{}') is not a finite number", where, key, k + 1,
                                     n[k].IsScalar() ? n[k].Scalar() : std::string("a list or map")));
    out.push_back(v);
  }
  return out;
}

// Seconds, or ROS's duration {secs, nsecs} (ROS 2: {sec, nanosec}).
double yaml_time(const YAML::Node& n, const std::string& where, const std::string& path,
                 std::vector<std::string>& problems) {
  double v = 0;
  if (n.IsScalar()) {
    if (!parse_double(n.Scalar(), v))
      problems.push_back(fmt::format("{}: time_from_start '{}' is not a number of seconds", where, n.Scalar()));
    return v;
  }
  if (!n.IsMap()) {
    problems.push_back(fmt::format("{}: time_from_start must be seconds (2.5) or {{secs: 2, nsecs: 500000000}}", where));
    return v;
  }
  check_keys(n, {"secs", "nsecs", "sec", "nanosec"}, path, "time_from_start", problems);
  double secs = 0, nsecs = 0;
  bool any = false;
  for (const auto& [key, scale] : {std::pair<const char*, double>{"secs", 1}, {"sec", 1}, {"nsecs", 1e-9}, {"nanosec", 1e-9}}) {
    if (!n[key]) continue;
    any = true;
    double x = 0;
    if (!n[key].IsScalar() || !parse_double(n[key].Scalar(), x) || x != std::floor(x) || x < 0)
      problems.push_back(fmt::format("{}: time_from_start/{} must be a whole number >= 0", where, key));
    (scale == 1 ? secs : nsecs) += x * scale;
  }
  if (!any) problems.push_back(fmt::format("{}: time_from_start has neither secs nor nsecs", where));
  return secs + nsecs;
}

void throw_if(const std::vector<std::string>& problems) {
  if (!problems.empty()) throw ModelError(problems);
}

}  // namespace

TrajectoryGoal parse_point_args(const std::vector<std::string>& args) {
  TrajectoryGoal goal;
  std::vector<std::string> problems;
  for (size_t i = 0; i < args.size(); ++i) {
    GoalPoint p;
    p.where = fmt::format("--point {} ('{}')", i + 1, args[i]);
    const std::vector<std::string> parts = split(args[i], ':');
    if (parts.size() < 2 || parts.size() > 3) {
      problems.push_back(fmt::format("{}: expected TIME:POSITIONS or TIME:POSITIONS:VELOCITIES, e.g. 2.0:0.1,0.2 "
                                     "(seconds from the start, then one value per joint, comma-separated)",
                                     p.where));
      continue;
    }
    if (!parse_double(parts[0], p.time))
      problems.push_back(fmt::format("{}: time '{}' is not a number; the field before the first ':' is the time from "
                                     "the start in seconds",
                                     p.where, trim(parts[0])));
    p.positions = number_list(parts[1], p.where, "positions", problems);
    if (parts.size() == 3) p.velocities = number_list(parts[2], p.where, "velocities", problems);
    goal.points.push_back(std::move(p));
  }
  throw_if(problems);
  return goal;
}

TrajectoryGoal parse_goal_yaml(const std::string& text, const std::string& path) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ModelError(fmt::format("{}:{}: malformed YAML: {}", path, e.mark.line + 1, e.msg));
  }
  if (!root.IsMap())
    throw ModelError(fmt::format("{}: expected a map with joint_names and points (trajectory_msgs/JointTrajectory's "
                                 "layout: joint_names: [j1, j2], points: [{{positions: [0.1, 0.2], time_from_start: 2}}])",
                                 path));
  std::vector<std::string> problems;
  check_keys(root, {"joint_names", "points", "header"}, path, "the trajectory", problems);
  TrajectoryGoal goal;
  if (const YAML::Node names = root["joint_names"]) {
    goal.joints_where = line_of(path, names) + ": joint_names";
    if (!names.IsSequence())
      problems.push_back(goal.joints_where + " must be a list of joint names, e.g. [j1, j2]");
    else
      for (const auto& n : names) {
        if (n.IsScalar())
          goal.joints.push_back(n.Scalar());
        else
          problems.push_back(fmt::format("{}: joint_names entries must be names", line_of(path, n)));
      }
  }
  const YAML::Node points = root["points"];
  if (!points) {
    problems.push_back(fmt::format("{}: no 'points'; add points: [{{positions: [...], time_from_start: SECONDS}}]", path));
  } else if (!points.IsSequence() || points.size() == 0) {
    problems.push_back(fmt::format("{}: points must be a non-empty list of {{positions: [...], time_from_start: SECONDS}}",
                                   line_of(path, points)));
  } else {
    for (size_t k = 0; k < points.size(); ++k) {
      const YAML::Node n = points[k];
      GoalPoint p;
      p.where = fmt::format("{}: point {}", line_of(path, n), k + 1);
      if (!n.IsMap()) {
        problems.push_back(p.where + ": expected a map {positions: [...], time_from_start: SECONDS}");
        continue;
      }
      check_keys(n, {"positions", "velocities", "accelerations", "effort", "time_from_start"}, path,
                 fmt::format("point {}", k + 1), problems);
      if (n["positions"])
        p.positions = yaml_numbers(n["positions"], p.where, "positions", problems);
      else
        problems.push_back(p.where + ": no positions; add positions: [...] with one value per joint");
      if (n["velocities"]) p.velocities = yaml_numbers(n["velocities"], p.where, "velocities", problems);
      if (n["accelerations"]) p.accelerations = yaml_numbers(n["accelerations"], p.where, "accelerations", problems);
      if (n["effort"] && !(n["effort"].IsSequence() && n["effort"].size() == 0))
        problems.push_back(p.where + ": effort is not used by a JointTrajectoryController; remove it (or leave it [])");
      if (n["time_from_start"])
        p.time = yaml_time(n["time_from_start"], p.where, path, problems);
      else
        problems.push_back(p.where + ": no time_from_start; add time_from_start: SECONDS (or {secs: S, nsecs: N})");
      goal.points.push_back(std::move(p));
    }
  }
  throw_if(problems);
  return goal;
}

TrajectoryGoal parse_goal_csv(const std::string& text, const std::string& path) {
  TrajectoryGoal goal;
  std::vector<std::string> problems;
  size_t columns = 0;
  std::string header;
  const std::vector<std::string> lines = split(text, '\n');
  for (size_t k = 0; k < lines.size(); ++k) {
    const std::string line = trim(lines[k]);
    if (line.empty() || line[0] == '#') continue;
    const std::string where = fmt::format("{}:{}", path, k + 1);
    std::vector<std::string> cells = split(line, ',');
    for (auto& c : cells) c = trim(c);
    if (columns == 0) {
      header = line;
      columns = cells.size();
      goal.joints_where = where + ": header";
      if (cells[0] != "time" && cells[0] != "time_from_start")
        throw ModelError(fmt::format("{}: the header must be time,<joint>,<joint>,... (the first column is the time "
                                     "from the start in seconds), not '{}'",
                                     where, line));
      if (cells.size() < 2) throw ModelError(where + ": the header names no joint; write time,<joint>,<joint>,...");
      goal.joints.assign(cells.begin() + 1, cells.end());
      continue;
    }
    GoalPoint p;
    p.where = where;
    if (cells.size() != columns) {
      problems.push_back(fmt::format("{}: {} for the {} columns of the header ({}); give the time and one position per "
                                     "joint",
                                     where, count_of(cells.size(), "value"), columns, header));
      continue;
    }
    if (!parse_double(cells[0], p.time))
      problems.push_back(fmt::format("{}: time '{}' is not a number of seconds", where, cells[0]));
    for (size_t c = 1; c < cells.size(); ++c) {
      double v = 0;
      if (!parse_double(cells[c], v))
        problems.push_back(
            fmt::format("{}: '{}' (column '{}') is not a finite number", where, cells[c], goal.joints[c - 1]));
      p.positions.push_back(v);
    }
    goal.points.push_back(std::move(p));
  }
  if (columns == 0) throw ModelError(path + ": empty; the first line must be the header time,<joint>,<joint>,...");
  if (goal.points.empty() && problems.empty())
    problems.push_back(path + ": no rows after the header; add one row per point: TIME,<position per joint>");
  throw_if(problems);
  return goal;
}

void set_joints_from_flag(TrajectoryGoal& goal, const std::string& joints_flag) {
  std::vector<std::string> names = split(joints_flag, ',');
  for (auto& n : names) n = trim(n);
  if (!goal.joints.empty() && goal.joints != names)
    throw ModelError(fmt::format("--joints {} does not match {} ({}); name the joints in one place",
                                 joints_flag, goal.joints_where, fmt::join(goal.joints, ",")));
  goal.joints = names;
  goal.joints_where = "--joints";
}

void check_goal(const TrajectoryGoal& goal) {
  std::vector<std::string> problems;
  const size_t n = goal.joints.size();
  if (n == 0) problems.push_back("no joints: name them with --joints (or joint_names in the file)");
  std::set<std::string> seen;
  for (size_t k = 0; k < n; ++k) {
    if (goal.joints[k].empty())
      problems.push_back(fmt::format("{}: joint {} has an empty name", goal.joints_where, k + 1));
    else if (!seen.insert(goal.joints[k]).second)
      problems.push_back(fmt::format("{}: joint '{}' is listed twice", goal.joints_where, goal.joints[k]));
  }
  if (goal.points.empty()) problems.push_back("no points: give --point TIME:POSITIONS, --file or --csv");
  const std::string joints_text = fmt::format("{}; from {}", fmt::join(goal.joints, ", "), goal.joints_where);
  double prev = 0;
  for (size_t i = 0; i < goal.points.size(); ++i) {
    const GoalPoint& p = goal.points[i];
    if (n > 0 && p.positions.size() != n)
      problems.push_back(fmt::format("{}: {} for {} ({}); give one value per joint", p.where,
                                     count_of(p.positions.size(), "position"), count_of(n, "joint"), joints_text));
    if (n > 0 && !p.velocities.empty() && p.velocities.size() != n)
      problems.push_back(fmt::format("{}: {} for {} ({}); give none or one per joint", p.where,
                                     count_of(p.velocities.size(), "velocity"), count_of(n, "joint"), joints_text));
    if (!p.accelerations.empty() && (p.velocities.empty() || p.accelerations.size() != n))
      problems.push_back(fmt::format("{}: accelerations need velocities, and one value per joint", p.where));
    for (const auto* v : {&p.positions, &p.velocities, &p.accelerations})
      for (double x : *v)
        if (!std::isfinite(x)) {
          problems.push_back(fmt::format("{}: {} is not a finite number", p.where, x));
          break;
        }
    if (!std::isfinite(p.time) || p.time <= prev)
      problems.push_back(
          i == 0 ? fmt::format("{}: time {} must be > 0 (seconds from the start; at 0 the joints are where they are)",
                               p.where, p.time)
                 : fmt::format("{}: time {} must be after the previous point's {} (times count from the start and "
                               "increase)",
                               p.where, p.time, prev));
    if (std::isfinite(p.time)) prev = std::max(prev, p.time);
  }
  throw_if(problems);
}

void add_offsets(TrajectoryGoal& goal, const std::vector<double>& start) {
  for (auto& p : goal.points)
    for (size_t k = 0; k < p.positions.size() && k < start.size(); ++k) p.positions[k] += start[k];
}

joint_trajectory_t to_message(const TrajectoryGoal& goal, int64_t goal_id, int64_t utime) {
  joint_trajectory_t m{};
  m.utime = utime;
  m.goal_id = goal_id;
  m.joint_names = goal.joints;
  m.num_joints = int32_t(goal.joints.size());
  for (const auto& p : goal.points) {
    trajectory_point_t t{};
    t.time_from_start = p.time;
    t.positions = p.positions;
    t.num_positions = int32_t(p.positions.size());
    t.velocities = p.velocities;
    t.num_velocities = int32_t(p.velocities.size());
    t.accelerations = p.accelerations;
    t.num_accelerations = int32_t(p.accelerations.size());
    m.points.push_back(std::move(t));
  }
  m.num_points = int32_t(m.points.size());
  return m;
}

const controller_info_t& trajectory_controller(const std::vector<controller_info_t>& listed, const std::string& name,
                                              const std::string& prefix) {
  return commandable(listed, name, {joint_trajectory_t::getTypeName(), 0}, "(a controller of the ros_control YAML)",
                     prefix);
}

std::string controller_name(const std::string& target) {
  std::string name = without_leading_slashes(target);
  while (!name.empty() && name.back() == '/') name.pop_back();
  const std::string suffix = "/command";
  if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
    name.erase(name.size() - suffix.size());
  return name;
}

std::string status_name(int8_t status) {
  switch (status) {
    case trajectory_status_t::ACTIVE: return "ACTIVE";
    case trajectory_status_t::SUCCEEDED: return "SUCCEEDED";
    case trajectory_status_t::REJECTED: return "REJECTED";
    case trajectory_status_t::PATH_TOLERANCE_VIOLATED: return "PATH_TOLERANCE_VIOLATED";
    case trajectory_status_t::GOAL_TOLERANCE_VIOLATED: return "GOAL_TOLERANCE_VIOLATED";
    case trajectory_status_t::PREEMPTED: return "PREEMPTED";
    case trajectory_status_t::ABORTED: return "ABORTED";
    default: return fmt::format("status {}", int(status));
  }
}

}  // namespace lcm_control::tools
