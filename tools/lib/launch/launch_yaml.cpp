// Our YAML launch format: see config/turret_bot.launch.yaml for the keys.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "description/robot_model.hpp"
#include "description/substitution.hpp"
#include "description/text.hpp"
#include "tools/lib/launch/launch_file.hpp"

namespace fs = std::filesystem;

namespace lcm_control::tools {

// YAML: see config/turret_bot.launch.yaml for the keys.

LaunchPlan read_launch_yaml(const std::string& path, const std::vector<std::string>& package_path,
                            const std::set<std::string>& embedding_keys) {
  const YAML::Node root = read_yaml_map(path, "launch keys (urdf, config, ...)");
  const std::string dir = fs::absolute(path).parent_path().string();
  LaunchPlan plan;
  plan.file = path;
  std::vector<std::string> problems;
  auto where = [&](const YAML::Node& n, const std::string& key) {
    return fmt::format("{}:{}: '{}'", path, n.Mark().line + 1, key);
  };
  auto str = [&](const YAML::Node& n, const std::string& key) {
    if (!n.IsScalar()) {
      problems.push_back(where(n, key) + " must be a single value");
      return std::string();
    }
    return substitute(n.as<std::string>(), Substitutions{package_path, {}, kLaunchArgFix}, where(n, key));
  };
  auto list = [&](const YAML::Node& n, const std::string& key) {
    std::vector<std::string> out;
    if (n.IsScalar()) return split_words(str(n, key));
    if (!n.IsSequence()) {
      problems.push_back(where(n, key) + " must be a list");
      return out;
    }
    for (const auto& e : n) out.push_back(str(e, key));
    return out;
  };
  auto number = [&](const YAML::Node& n, const std::string& key) {
    try {
      const double v = n.as<double>();
      if (v > 0) return v;
    } catch (const YAML::Exception&) {
    }
    problems.push_back(where(n, key) + " must be a positive number");
    return 0.0;
  };
  auto number_any = [&](const YAML::Node& n, const std::string& key) {
    try {
      const double v = n.as<double>();
      if (std::isfinite(v)) return v;
    } catch (const YAML::Exception&) {
    }
    problems.push_back(where(n, key) + " must be a number");
    return 0.0;
  };
  auto boolean = [&](const YAML::Node& n, const std::string& key) {
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      problems.push_back(where(n, key) + " must be true or false");
      return false;
    }
  };
  const std::set<std::string> known = {"urdf",         "config",          "mode",            "cpu",
                                       "physics_rate", "control_rate",    "sim_server_args",
                                       "controller_manager_args", "controllers", "spawn", "inactive", "spawner_args",
                                       "state_publisher", "processes",  "commands", "namespace", "args",
                                       "initial_positions", "paused", "robots", "hardware_lcm_url", "hardware_url", "hardware_mirror",
                                       "rt_priority", "spin_us", "xacro_args", "base", "base_pose", "simulate_hardware"};
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& v = kv.second;
    try {
      if (embedding_keys.count(key)) {
        continue;
      } else if (!known.count(key)) {
        problems.push_back(fmt::format("{}: unknown key; valid keys: {}", where(kv.first, key), fmt::join(known, ", ")));
      } else if (key == "urdf") {
        plan.urdf = absolute_from(str(v, key), dir);
      } else if (key == "config") {
        for (const auto& c : v.IsSequence() ? list(v, key) : std::vector<std::string>{str(v, key)})
          plan.configs.push_back(absolute_from(c, dir));
      } else if (key == "mode") {
        plan.mode = str(v, key);
        if (plan.mode != "realtime" && plan.mode != "lockstep")
          problems.push_back(where(v, key) + " must be realtime or lockstep, not '" + plan.mode + "'");
      } else if (key == "cpu") {
        plan.cpu = str(v, key);
        if (const std::string problem = check_cpu(plan.cpu); !problem.empty())
          problems.push_back(where(v, key) + " " + problem);
      } else if (key == "spin_us" && v.IsScalar() && v.Scalar() == "auto") {
        plan.spin_us = -1;
      } else if (key == "rt_priority" || key == "spin_us") {
        const int most = key == "rt_priority" ? kMaxRtPriority : kMaxSpinUs;
        const double n = number_any(v, key);  // says so if it is not a number
        if (n < 0 || n > most || n != double(int(n)))
          problems.push_back(fmt::format("{} must be a whole number from 0 to {}{}", where(v, key), most,
                                         key == "rt_priority" ? " (0: the normal scheduler; 1-99: SCHED_FIFO)"
                                                              : " (microseconds), or auto"));
        else
          (key == "rt_priority" ? plan.rt_priority : plan.spin_us) = int(n);
      } else if (key == "physics_rate") {
        plan.physics_rate = number(v, key);
      } else if (key == "control_rate") {
        plan.control_rate = number(v, key);
      } else if (key == "sim_server_args") {
        plan.sim_args = list(v, key);
      } else if (key == "controller_manager_args") {
        plan.cm_args = list(v, key);
      } else if (key == "controllers" || key == "spawn") {
        if (!plan.controllers.empty())
          problems.push_back(where(v, key) + ": give controllers or spawn (the same list), not both");
        plan.controllers = list(v, key);
      } else if (key == "inactive") {
        plan.inactive = list(v, key);
      } else if (key == "spawner_args") {
        plan.spawner_args = list(v, key);
      } else if (key == "state_publisher") {
        plan.state_publisher = boolean(v, key);
      } else if (key == "paused") {
        plan.paused = boolean(v, key);
      } else if (key == "simulate_hardware") {
        plan.simulate_hardware = list(v, key);
      } else if (key == "base") {
        plan.base = str(v, key);
        if (plan.base == "auto") plan.base.clear();
        if (!plan.base.empty() && plan.base != "fixed" && plan.base != "floating")
          problems.push_back(where(v, key) + ": '" + plan.base + "': give fixed (welded where it starts), floating "
                             "(free) or auto (free unless the URDF welds it to `world`, as Gazebo)");
      } else if (key == "base_pose") {
        const std::vector<std::string> xyzyaw = list(v, key);
        std::array<double, 4> pose{};
        bool ok = xyzyaw.size() == 4;
        for (size_t k = 0; ok && k < 4; ++k) ok = parse_double(xyzyaw[k], pose[k]) && std::isfinite(pose[k]);
        if (!ok)
          problems.push_back(where(v, key) + ": give four numbers, [x, y, z, yaw] in m and rad");
        else
          plan.base_pose = pose;
      } else if (key == "namespace") {
        plan.ns = normalize_namespace(str(v, key));
      } else if (key == "hardware_lcm_url" || key == "hardware_url") {
        plan.hardware_lcm_url = str(v, key);
      } else if (key == "hardware_mirror") {
        plan.hardware_mirror_hz = number(v, key);
      } else if (key == "robots") {
        if (v.IsSequence()) {
          for (const auto& r : list(v, key)) plan.robots.push_back(normalize_namespace(r));
        } else {
          const double n = number(v, key);
          if (n < 1 || n > kMaxRobots || n != double(int(n)))
            problems.push_back(fmt::format("{} must be a whole number of robots from 1 to {} (namespaces r0, r1, "
                                           "...), or a list of namespaces",
                                           where(v, key), kMaxRobots));
          else
            plan.robots = robot_names(int(n));
        }
        for (size_t i = 0; i < plan.robots.size(); ++i)
          for (size_t j = 0; j < i; ++j)
            if (plan.robots[i] == plan.robots[j] || plan.robots[i].empty())
              problems.push_back(fmt::format("{}: namespace '{}' is empty or given twice: each robot needs its own",
                                             where(v, key), plan.robots[i]));
      } else if (key == "args") {
        if (!v.IsMap()) {
          problems.push_back(where(v, key) + " must be a map NAME: VALUE (the $(arg NAME) values of the YAML)");
          continue;
        }
        for (const auto& a : v) {
          const std::string name = a.first.as<std::string>();
          plan.args.emplace_back(name, str(a.second, "args." + name));
        }
      } else if (key == "xacro_args") {
        if (v.IsNull()) continue;  // `xacro_args:` with nothing under it
        if (!v.IsMap()) {
          problems.push_back(where(v, key) + " must be a map NAME: VALUE (the <xacro:arg> values of a .xacro urdf)");
          continue;
        }
        for (const auto& a : v) {
          const std::string name = a.first.as<std::string>();
          plan.xacro_args.emplace_back(name, str(a.second, "xacro_args." + name));
        }
      } else if (key == "initial_positions") {
        if (!v.IsMap()) {
          problems.push_back(where(v, key) + " must be a map JOINT: POSITION (rad or m), e.g. {joint4: -2.0}");
          continue;
        }
        for (const auto& j : v) {
          const std::string joint = j.first.as<std::string>();
          plan.initial_positions.emplace_back(joint, number_any(j.second, "initial_positions." + joint));
        }
      } else if (key == "commands") {
        if (!v.IsSequence()) {
          problems.push_back(where(v, key) + " must be a list of {target, expr, rate, count, duration}");
          continue;
        }
        for (const auto& c : v) {
          if (!c.IsMap() || !c["target"] || !c["expr"]) {
            problems.push_back(where(c, key) + " entries need target and expr");
            continue;
          }
          CommandSpec spec;
          for (const auto& ck : c) {
            const std::string k = ck.first.as<std::string>();
            const YAML::Node& cv = ck.second;
            if (k == "target") {
              spec.target = str(cv, "commands.target");
            } else if (k == "expr") {
              if (cv.IsScalar()) {
                spec.expr = {str(cv, "commands.expr")};
              } else {
                spec.expr = list(cv, "commands.expr");
              }
            } else if (k == "rate") {
              spec.rate = number(cv, "commands.rate");
            } else if (k == "duration") {
              spec.duration = number(cv, "commands.duration");
            } else if (k == "count") {
              spec.count = int64_t(number(cv, "commands.count"));
              if (double(spec.count) != cv.as<double>(0.0))
                problems.push_back(where(cv, "commands.count") + " must be a whole number");
            } else {
              problems.push_back(where(ck.first, "commands." + k) +
                                 ": unknown key; valid: target, expr, rate, count, duration");
            }
          }
          if (spec.expr.empty()) problems.push_back(where(c, key) + " '" + spec.target + "' has no expression");
          plan.commands.push_back(spec);
        }
      } else if (key == "processes") {
        if (!v.IsSequence()) {
          problems.push_back(where(v, key) + " must be a list of {name, command, required}");
          continue;
        }
        for (const auto& p : v) {
          ProcessSpec spec;
          spec.required = false;
          if (!p.IsMap() || !p["name"] || !p["command"]) {
            problems.push_back(where(p, key) + " entries need name and command");
            continue;
          }
          for (const auto& pk : p) {
            const std::string k = pk.first.as<std::string>();
            if (k != "name" && k != "command" && k != "required")
              problems.push_back(where(pk.first, "processes." + k) + ": unknown key; valid: name, command, required");
          }
          spec.name = str(p["name"], "processes.name");
          spec.argv = list(p["command"], "processes.command");
          if (p["required"]) spec.required = boolean(p["required"], "processes.required");
          if (spec.argv.empty()) problems.push_back(where(p, key) + " '" + spec.name + "' has an empty command");
          plan.processes.push_back(spec);
        }
      }
    } catch (const ModelError& e) {
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
    }
  }
  for (const auto& c : plan.commands)
    if (std::find(plan.controllers.begin(), plan.controllers.end(), c.target) == plan.controllers.end())
      problems.push_back(fmt::format("{}: commands: target '{}' is not one of the spawned controllers ({})", path,
                                     c.target, plan.controllers.empty() ? "none" : fmt::format("{}", fmt::join(plan.controllers, ", "))));
  if (plan.urdf.empty()) problems.push_back(fmt::format("{}: 'urdf' is missing: the robot's URDF file", path));
  if (!problems.empty()) throw ModelError(problems);
  return plan;
}

}  // namespace lcm_control::tools
