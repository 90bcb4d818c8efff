// The ROS 2 parameter file of ros2_control: `controller_manager: ros__parameters:`
// with update_rate and the controllers' types, and each controller's own
// `<name>: ros__parameters:` section (where `type:` may be given too), read
// with rclcpp's rules: a node's sections are every entry whose node path
// matches it (`/**`, `/**/name`, `/ns/name`, `name`; nested keys are namespace
// levels), merged wildcard entries first, then the specific ones (deep merge of
// maps), and dotted keys (`linear.x.max_velocity`) are nested maps. The result
// is the same ControllerSpec list a ROS 1 YAML gives (name, type as written,
// params = the merged section with `type` in it).
#pragma once

#include <functional>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

namespace lcm_control {

struct RobotModel;

// True for a ROS 2 parameter file: some node section (top-level key, or nested namespace keys) holds
// `ros__parameters`.
bool is_ros2_parameter_file(const YAML::Node& doc);
// Fills model.controllers, model.update_rate_hz and model.config_section (a namespace taken from the file);
// throws ModelError with every problem (file and key path named).
void parse_ros2_params(RobotModel& model, const YAML::Node& doc, const std::string& file);

// `a.b.c: v` -> `a: {b: {c: v}}`, at every level, merged with the keys already nested there.
YAML::Node expand_dotted_keys(const YAML::Node& node);
// Deep merge: maps merge key by key, anything else in `from` replaces what `into` has. on_set, if given, hears of
// each value `from` puts in place (not the maps merged further): its key path ("a/b/c"), the value, and whether it
// replaced one.
using MergeListener = std::function<void(const std::string& path, const YAML::Node& value, bool replaced)>;
void deep_merge(YAML::Node& into, const YAML::Node& from, const MergeListener& on_set = {});
// rclcpp's node-name matching: `pattern` and `fqn` are node paths ("/**/arm", "/ns/arm"); `**` stands for any
// number of namespace levels, `*` for exactly one; a name without a leading '/' is in the root namespace.
bool node_path_matches(const std::string& pattern, const std::string& fqn);

}  // namespace lcm_control
