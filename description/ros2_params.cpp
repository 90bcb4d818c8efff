#include "description/ros2_params.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "description/robot_model.hpp"
#include "description/text.hpp"

namespace lcm_control {

namespace {

constexpr const char* kParamsKey = "ros__parameters";

bool has_key(const YAML::Node& map, const std::string& key) {
  if (!map.IsMap()) return false;
  for (const auto& kv : map)
    if (kv.first.Scalar() == key) return true;
  return false;
}

std::vector<std::string> tokens(const std::string& path) {
  std::vector<std::string> out;
  for (const auto& t : split(path, '/'))
    if (!t.empty()) out.push_back(t);
  return out;
}

bool match(const std::vector<std::string>& p, size_t i, const std::vector<std::string>& n, size_t k) {
  if (i == p.size()) return k == n.size();
  if (p[i] == "**") {
    for (size_t m = k; m <= n.size(); ++m)
      if (match(p, i + 1, n, m)) return true;
    return false;
  }
  if (k == n.size()) return false;
  return (p[i] == "*" || p[i] == n[k]) && match(p, i + 1, n, k + 1);
}

bool has_wildcard(const std::vector<std::string>& t) {
  return std::any_of(t.begin(), t.end(), [](const std::string& s) { return s.find('*') != std::string::npos; });
}

// One node section: the node path its keys give and its ros__parameters.
struct Section {
  std::vector<std::string> path;  // tokens, e.g. {"**", "controller_manager"}
  std::string written;            // the keys as written, joined by '/'
  YAML::Node params;              // dotted keys expanded
};

// Collects the sections under `node` (a map of node names / namespaces); returns whether it found any.
bool collect(const YAML::Node& node, const std::vector<std::string>& path, const std::string& written,
             const std::string& file, std::vector<Section>& out, std::vector<std::string>& problems, int depth) {
  bool found = false;
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    if (key == kParamsKey) {
      found = true;
      if (kv.second.IsNull()) {
        out.push_back(Section{path, written, YAML::Node(YAML::NodeType::Map)});
      } else if (!kv.second.IsMap()) {
        problems.push_back(fmt::format("{}: {}/{}: expected a map of parameters", file, written, key));
      } else {
        out.push_back(Section{path, written, expand_dotted_keys(kv.second)});
      }
      continue;
    }
    if (!kv.second.IsMap() || depth > 8) continue;
    std::vector<std::string> p = path;
    for (const auto& t : tokens(key)) p.push_back(t);
    found |= collect(kv.second, p, written.empty() ? key : written + "/" + key, file, out, problems, depth + 1);
  }
  return found;
}

// The merged parameters of node `fqn`: wildcard sections first, then the specific ones, each in file order.
YAML::Node merged(const std::vector<Section>& sections, const std::vector<std::string>& fqn) {
  YAML::Node out(YAML::NodeType::Map);
  for (int pass = 0; pass < 2; ++pass)
    for (const auto& s : sections)
      if (has_wildcard(s.path) == (pass == 0) && match(s.path, 0, fqn, 0)) deep_merge(out, s.params);
  return out;
}

std::string scalar_or_empty(const YAML::Node& n) { return n && n.IsScalar() ? trim(n.Scalar()) : ""; }

// controller_manager's hardware_components_initial_state (a map of unconfigured / inactive lists, or the dotted
// keys "hardware_components_initial_state.unconfigured"): the components that do not start active.
void read_initial_states(const std::string& file, const std::string& key, const YAML::Node& value, RobotModel& model,
                         std::vector<std::string>& problems) {
  auto read_list = [&](const std::string& state, const YAML::Node& list) {
    const std::string where =
        fmt::format("{}: controller_manager/ros__parameters/hardware_components_initial_state/{}", file, state);
    std::vector<std::string>* into = state == "unconfigured" ? &model.components_start_unconfigured
                                     : state == "inactive"   ? &model.components_start_inactive
                                                             : nullptr;
    if (!into)
      return problems.push_back(fmt::format("{}: '{}' is not a state a component can start in (unconfigured or "
                                            "inactive; the others start active)",
                                            where, state));
    if (list.IsScalar() && !trim(list.Scalar()).empty()) return into->push_back(trim(list.Scalar()));
    if (!list.IsSequence())
      return problems.push_back(fmt::format("{}: expected a list of <ros2_control> names", where));
    for (const auto& n : list) {
      if (!n.IsScalar() || trim(n.Scalar()).empty())
        return problems.push_back(fmt::format("{}: expected a list of <ros2_control> names", where));
      into->push_back(trim(n.Scalar()));
    }
  };
  if (key != "hardware_components_initial_state") return read_list(key.substr(key.find('.') + 1), value);
  if (!value.IsMap())
    return problems.push_back(fmt::format("{}: controller_manager/ros__parameters/hardware_components_initial_state: "
                                          "expected a map with unconfigured: [...] and inactive: [...]",
                                          file));
  for (const auto& kv : value) read_list(kv.first.Scalar(), kv.second);
}

}  // namespace

bool node_path_matches(const std::string& pattern, const std::string& fqn) {
  return match(tokens(pattern), 0, tokens(fqn), 0);
}

namespace {
void deep_merge_at(YAML::Node& into, const YAML::Node& from, const std::string& prefix, const MergeListener& on_set) {
  for (const auto& kv : from) {
    const std::string key = kv.first.Scalar();
    const bool had = has_key(into, key);
    if (kv.second.IsMap() && had && into[key].IsMap()) {
      YAML::Node sub = into[key];
      deep_merge_at(sub, kv.second, prefix + key + "/", on_set);
    } else {
      into[key] = YAML::Clone(kv.second);
      if (on_set) on_set(prefix + key, kv.second, had);
    }
  }
}
}  // namespace

void deep_merge(YAML::Node& into, const YAML::Node& from, const MergeListener& on_set) {
  deep_merge_at(into, from, "", on_set);
}

YAML::Node expand_dotted_keys(const YAML::Node& node) {
  if (!node.IsMap()) return YAML::Clone(node);
  YAML::Node out(YAML::NodeType::Map);
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    std::vector<std::string> parts = split(key, '.');
    if (std::any_of(parts.begin(), parts.end(), [](const std::string& s) { return s.empty(); })) parts = {key};
    YAML::Node value = expand_dotted_keys(kv.second);
    for (size_t i = parts.size() - 1; i > 0; --i) {
      YAML::Node level(YAML::NodeType::Map);
      level[parts[i]] = value;
      value = level;
    }
    YAML::Node one(YAML::NodeType::Map);
    one[parts[0]] = value;
    deep_merge(out, one);
  }
  return out;
}

bool is_ros2_parameter_file(const YAML::Node& doc) {
  if (!doc.IsMap()) return false;
  std::vector<Section> sections;
  std::vector<std::string> ignored;
  for (const auto& kv : doc)
    if (kv.first.Scalar() == kParamsKey || (kv.second.IsMap() && has_key(kv.second, kParamsKey))) return true;
  return collect(doc, {}, "", "", sections, ignored, 0);
}

void parse_ros2_params(RobotModel& model, const YAML::Node& doc, const std::string& file) {
  std::vector<std::string> problems;
  std::vector<Section> sections;
  for (const auto& kv : doc) {
    const std::string key = kv.first.Scalar();
    if (key == kParamsKey) {
      problems.push_back(fmt::format("{}: ros__parameters at the top level belongs under a node name, e.g. "
                                     "controller_manager: ros__parameters: ...",
                                     file));
      continue;
    }
    bool found = false;
    if (kv.second.IsMap()) {
      YAML::Node one(YAML::NodeType::Map);
      one[key] = kv.second;
      found = collect(one, {}, "", file, sections, problems, 0);
    }
    if (!found)
      model.warnings.push_back(fmt::format("{}: top-level entry '{}' holds no ros__parameters (neither a controller "
                                           "nor the controller_manager); it is ignored",
                                           file, key));
  }

  // The robot's namespace: the one given, else the only one the file's own (non-wildcard) sections name.
  std::vector<std::string> ns = tokens(model.ns);
  bool any_here = false;
  std::vector<std::string> namespaces;
  for (const auto& s : sections) {
    if (has_wildcard(s.path) || s.path.empty()) continue;
    const std::vector<std::string> sns(s.path.begin(), s.path.end() - 1);
    if (sns == ns) any_here = true;
    const std::string joined = join(sns, "/");
    if (!sns.empty() && std::find(namespaces.begin(), namespaces.end(), joined) == namespaces.end())
      namespaces.push_back(joined);
  }
  if (!any_here && ns.empty() && namespaces.size() == 1) {
    model.config_section = namespaces.front();
    ns = tokens(namespaces.front());
    model.notes.push_back(fmt::format("{}: parameters read for namespace '/{}', the only one the file names (run with "
                                      "--namespace {} to have its channels there too)",
                                      file, namespaces.front(), namespaces.front()));
  } else if (!any_here && ns.empty() && namespaces.size() > 1) {
    problems.push_back(fmt::format("{}: the nodes are in several namespaces ({}); say which robot with --namespace "
                                   "NAME",
                                   file, join(namespaces)));
  }
  auto fqn = [&](const std::string& name) {
    std::vector<std::string> f = ns;
    f.push_back(name);
    return f;
  };

  // controller_manager: update_rate and the declared controllers.
  const YAML::Node cm = merged(sections, fqn("controller_manager"));
  std::vector<std::pair<std::string, std::string>> declared;  // name, type
  for (const auto& kv : cm) {
    const std::string key = kv.first.Scalar();
    if (key == "update_rate") {
      double hz = 0;
      if (!kv.second.IsScalar() || !parse_double(kv.second.Scalar(), hz) || hz <= 0)
        problems.push_back(fmt::format("{}: controller_manager/ros__parameters/update_rate: '{}' is not a positive "
                                       "number (Hz)",
                                       file, kv.second.IsScalar() ? kv.second.Scalar() : "a map or list"));
      else
        model.update_rate_hz = hz;
    } else if (key == "hardware_components_initial_state" ||
               key.rfind("hardware_components_initial_state.", 0) == 0) {
      read_initial_states(file, key, kv.second, model, problems);
    } else if (kv.second.IsMap() && kv.second["type"]) {
      const std::string type = scalar_or_empty(kv.second["type"]);
      if (type.empty())
        problems.push_back(fmt::format("{}: controller_manager/ros__parameters/{}/type: expected a controller type "
                                       "name such as joint_trajectory_controller/JointTrajectoryController",
                                       file, key));
      else
        declared.emplace_back(key, type);
    }
  }

  // Every controller: declared ones in their order, then those whose own section names a type, in file order.
  std::vector<std::string> names;
  for (const auto& [n, t] : declared) names.push_back(n);
  for (const auto& s : sections) {
    if (s.path.empty() || s.path.back().find('*') != std::string::npos || s.path.back() == "controller_manager")
      continue;
    if (!match(s.path, 0, fqn(s.path.back()), 0)) continue;
    if (std::find(names.begin(), names.end(), s.path.back()) == names.end()) names.push_back(s.path.back());
  }
  for (const auto& name : names) {
    const YAML::Node own = merged(sections, fqn(name));
    std::string type;
    for (const auto& [n, t] : declared)
      if (n == name) type = t;
    if (own["type"]) {
      const std::string own_type = scalar_or_empty(own["type"]);
      if (own_type.empty()) {
        problems.push_back(fmt::format("{}: {}/ros__parameters/type: expected a controller type name such as "
                                       "joint_trajectory_controller/JointTrajectoryController",
                                       file, name));
        continue;
      }
      if (!type.empty() && own_type != type)
        model.warnings.push_back(fmt::format("{}: controller '{}' has type '{}' under controller_manager and '{}' in "
                                             "its own ros__parameters; using the controller_manager's, '{}'",
                                             file, name, type, own_type, type));
      if (type.empty()) type = own_type;
    }
    if (type.empty()) {
      model.warnings.push_back(fmt::format("{}: '{}' is neither a controller (no type under controller_manager: "
                                           "ros__parameters: {}: nor in its own ros__parameters) nor the "
                                           "controller_manager; it is ignored",
                                           file, name, name));
      continue;
    }
    YAML::Node params(YAML::NodeType::Map);
    params["type"] = type;
    for (const auto& kv : own)
      if (kv.first.Scalar() != "type") params[kv.first.Scalar()] = YAML::Clone(kv.second);
    model.controllers.push_back(ControllerSpec{name, type, params, file});
  }
  model.notes.push_back(fmt::format("{}: a ROS 2 parameter file: {} controller{}{}", file, model.controllers.size(),
                                    model.controllers.size() == 1 ? "" : "s",
                                    model.update_rate_hz
                                        ? fmt::format(", controller_manager update_rate {:g} Hz", *model.update_rate_hz)
                                        : ", no controller_manager update_rate"));
  if (!problems.empty()) throw ModelError(problems);
}

}  // namespace lcm_control
