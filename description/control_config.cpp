#include "description/control_config.hpp"

#include <fmt/format.h>

#include <cmath>
#include <set>

#include "description/input_file.hpp"
#include "description/ros2_params.hpp"
#include "description/substitution.hpp"
#include "description/text.hpp"

namespace lcm_control {

namespace {

bool holds_controllers(const YAML::Node& n) {
  if (!n.IsMap()) return false;
  for (const auto& kv : n) {
    if (kv.first.as<std::string>() == "gazebo_ros_control") return true;
    if (kv.second.IsMap() && kv.second["type"]) return true;
  }
  return false;
}

// The map at `ns` ("a/b" walks a: then b:), or an undefined node.
YAML::Node at_namespace(const YAML::Node& root, const std::string& ns) {
  YAML::Node n = root;
  size_t start = 0;
  while (start <= ns.size()) {
    const size_t slash = std::min(ns.find('/', start), ns.size());
    const std::string part = ns.substr(start, slash - start);
    if (!part.empty()) {
      if (!n.IsMap() || !n[part]) return YAML::Node(YAML::NodeType::Undefined);
      n = n[part];
    }
    start = slash + 1;
  }
  return n;
}

// Where in the file this robot's entries are: sets model.config_section and says why in model.notes.
YAML::Node select_section(RobotModel& model, const YAML::Node& root, const std::string& file) {
  if (!model.ns.empty()) {
    const YAML::Node n = at_namespace(root, model.ns);
    if (n.IsDefined() && holds_controllers(n)) {
      model.config_section = model.ns;
      model.notes.push_back(fmt::format("{}: controllers read from '{}:', the robot's namespace", file, model.ns));
      return n;
    }
  }
  if (holds_controllers(root)) return root;
  std::vector<std::string> nested;
  for (const auto& kv : root)
    if (holds_controllers(kv.second)) nested.push_back(kv.first.as<std::string>());
  if (nested.size() == 1) {
    model.config_section = nested.front();
    model.notes.push_back(fmt::format(
        "{}: controllers read from '{}:', the file's only top-level map holding controllers{}", file, nested.front(),
        model.ns.empty() ? fmt::format(" (as ROS loads it into namespace /{}; run with --namespace {} to have its "
                                       "channels there too)",
                                       nested.front(), nested.front())
                         : fmt::format(" (the robot's namespace is '{}')", model.ns)));
    return root[nested.front()];
  }
  if (nested.size() > 1)
    throw ModelError(fmt::format("{}: controllers are nested under several top-level keys ({}); say which robot with "
                                 "--namespace NAME (or <robotNamespace> in the URDF's gazebo_ros_control plugin)",
                                 file, join(nested)));
  return root;
}

}  // namespace

PidGains parse_pid_gains(const YAML::Node& n, const std::string& where, std::vector<std::string>& problems,
                         std::vector<std::string>& warnings) {
  PidGains g;
  static const std::set<std::string> known = {"p", "i", "d", "i_clamp", "i_clamp_min", "i_clamp_max", "antiwindup",
                                              "publish_state"};
  if (!n.IsMap()) {
    problems.push_back(fmt::format("{}: expected a map with p, i, d (got a {})", where, n.IsSequence() ? "list" : "scalar"));
    return g;
  }
  for (const auto& kv : n) {
    const std::string key = kv.first.as<std::string>();
    if (!known.count(key))
      problems.push_back(fmt::format("{}/{}: unknown key; valid keys are p, i, d, i_clamp, i_clamp_min, i_clamp_max, "
                                     "antiwindup",
                                     where, key));
  }
  auto num = [&](const char* key, double& out) {
    if (!n[key]) return false;
    try {
      out = n[key].as<double>();
      if (!std::isfinite(out)) throw YAML::Exception(YAML::Mark::null_mark(), "not finite");
      return true;
    } catch (const YAML::Exception&) {
      problems.push_back(fmt::format("{}/{}: '{}' is not a number", where, key, n[key].Scalar()));
      return false;
    }
  };
  if (!num("p", g.p))
    if (!n["p"]) problems.push_back(fmt::format("{}: no 'p' gain (required); add p: <value>", where));
  num("i", g.i);
  num("d", g.d);
  double c = 0;
  if (num("i_clamp", c)) {
    g.i_clamp_max = std::abs(c);
    g.i_clamp_min = -std::abs(c);
  }
  if (num("i_clamp_min", c)) g.i_clamp_min = -std::abs(c);
  if (num("i_clamp_max", c)) g.i_clamp_max = std::abs(c);
  if (n["antiwindup"]) {
    try {
      g.antiwindup = n["antiwindup"].as<bool>();
    } catch (const YAML::Exception&) {
      problems.push_back(fmt::format("{}/antiwindup: '{}' is not true or false", where, n["antiwindup"].Scalar()));
    }
  }
  if (g.i != 0 && g.i_clamp_min == 0 && g.i_clamp_max == 0)
    warnings.push_back(fmt::format("{}: i is {} but i_clamp is 0, so the integral term stays 0 (ros_control semantics); "
                                   "set i_clamp to use it",
                                   where, g.i));
  return g;
}



void parse_control_config(RobotModel& model, const YAML::Node& doc, const std::string& file) {
  std::vector<std::string> problems;
  if (!doc || doc.IsNull()) throw ModelError(fmt::format("{}: the file is empty; expected controllers as top-level keys", file));
  if (!doc.IsMap())
    throw ModelError(fmt::format("{}: expected a map of controllers at the top level (like `j1_controller: {{type: ...}}`)",
                                 file));
  model.update_rate_hz.reset();  // the file's own (a reload reads it again)
  model.components_start_unconfigured.clear();
  model.components_start_inactive.clear();
  model.ros2_parameter_file = is_ros2_parameter_file(doc);
  if (model.ros2_parameter_file) {  // controller_manager: ros__parameters:
    parse_ros2_params(model, doc, file);
    for (auto& c : model.controllers) c.file = file;
    return;
  }
  const YAML::Node root = select_section(model, doc, file);
  const std::string prefix = model.config_section.empty() ? "" : model.config_section + "/";
  // The file a key came from (with several --config files, the one that set it).
  const auto src = [&](const std::string& key) {
    return model.config_key_files.empty() ? file : model.config_file_of(prefix + key);
  };
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& v = kv.second;
    if (key == "gazebo_ros_control") {
      if (!v.IsMap()) {
        problems.push_back(fmt::format("{}: {}gazebo_ros_control: expected a map with pid_gains", src(key), prefix));
        continue;
      }
      for (const auto& g : v) {
        const std::string gk = g.first.as<std::string>();
        if (gk != "pid_gains") {
          model.warnings.push_back(
              fmt::format("{}: {}gazebo_ros_control/{}: not used (only pid_gains is read)", src(key + "/" + gk), prefix, gk));
          continue;
        }
        if (!g.second.IsMap()) {
          problems.push_back(fmt::format("{}: {}gazebo_ros_control/pid_gains: expected a map of joint names", src(key + "/pid_gains"), prefix));
          continue;
        }
        for (const auto& jg : g.second) {
          const std::string joint = jg.first.as<std::string>();
          model.pid_gains[joint] = parse_pid_gains(
              jg.second, fmt::format("{}: {}gazebo_ros_control/pid_gains/{}", src(key + "/pid_gains/" + joint), prefix, joint), problems,
              model.warnings);
        }
      }
      continue;
    }
    if (!v.IsMap() || !v["type"]) {
      model.warnings.push_back(fmt::format(
          "{}: {}entry '{}' is neither a controller (no 'type' key) nor gazebo_ros_control; it is ignored", src(key),
          prefix.empty() ? "top-level " : prefix, key));
      continue;
    }
    if (!v["type"].IsScalar() || trim(v["type"].Scalar()).empty()) {
      problems.push_back(fmt::format("{}: {}{}/type: expected a controller type name (`cmctl list-types` lists "
                                     "them)",
                                     src(key + "/type"), prefix, key));
      continue;
    }
    model.controllers.push_back(ControllerSpec{key, trim(v["type"].Scalar()), YAML::Clone(v), src(key)});
  }
  if (!problems.empty()) throw ModelError(problems);
}

namespace {

YAML::Node read_config_file(const RobotModel& model, const std::string& config_path) {
  const std::string text =
      substitute_file(read_input_file(config_path, "config", "--config"),
                      Substitutions{model.options.package_path, model.options.args,
                                    "give its value with --arg {0}=VALUE (launch files: args: {{{0}: VALUE}}), as "
                                    "roslaunch does for <rosparam subst_value=\"true\">"},
                      config_path);
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ModelError(fmt::format("{}:{}:{}: malformed YAML: {}", config_path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
}

// Records `file` as the origin of every leaf (a scalar, a list, an empty map) of `value`, set at `key`.
void record_leaves(std::map<std::string, std::string>& files, const std::string& key, const YAML::Node& value,
                   const std::string& file) {
  if (!value.IsMap() || value.size() == 0) {
    files[key] = file;
    return;
  }
  for (const auto& kv : value) record_leaves(files, key + "/" + kv.first.Scalar(), kv.second, file);
}

// The files merged in order, as rosparam loads them into one namespace; each key a later file replaces is one note
// naming it and both files, and model.config_key_files says where every key came from.
YAML::Node merge_config_files(RobotModel& model, const std::vector<std::string>& paths) {
  YAML::Node merged(YAML::NodeType::Map);
  for (const std::string& path : paths) {
    const YAML::Node doc = read_config_file(model, path);
    if (!doc || doc.IsNull()) throw ModelError(fmt::format("{}: the file is empty; expected controllers as top-level keys", path));
    if (!doc.IsMap())
      throw ModelError(fmt::format("{}: expected a map of controllers at the top level (like `j1_controller: {{type: "
                                   "...}}`)",
                                   path));
    deep_merge(merged, doc, [&](const std::string& key, const YAML::Node& value, bool replaced) {
      if (replaced)
        model.notes.push_back(fmt::format("{}: {} replaces the value from {} (a later --config file wins, as with "
                                          "rosparam)",
                                          path, key, model.config_file_of(key)));
      auto& files = model.config_key_files;
      for (auto it = files.lower_bound(key + "/"); it != files.end() && it->first.rfind(key + "/", 0) == 0;)
        it = files.erase(it);
      record_leaves(files, key, value, path);
    });
  }
  return merged;
}

}  // namespace

void load_control_config_into(RobotModel& model, const std::vector<std::string>& config_paths) {
  model.config_paths = config_paths;
  model.config_path = join(config_paths, " + ");
  model.config_key_files.clear();
  if (config_paths.size() == 1) return parse_control_config(model, read_config_file(model, config_paths[0]),
                                                            config_paths[0]);
  const YAML::Node merged = merge_config_files(model, config_paths);
  parse_control_config(model, merged, model.config_path);
}

}  // namespace lcm_control
