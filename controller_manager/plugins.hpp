// Loading controller libraries (plugin.hpp) named in the YAML: a controller's
// `plugin:` key, a path relative to the YAML's folder. Each library is opened
// once and stays loaded; its types join the registry. Every failure is a
// ModelError naming the file, the YAML key and what to do.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"
#include "controller_interface/registry.hpp"

namespace lcm_control::cm {

// The libraries the configured controllers name, resolved against the YAML's folder, each once.
std::vector<std::string> plugin_libraries(const RobotModel& model);

// Opens each library, checks its PluginAbi against ours and registers its types into `registry` (a type already
// there is refused). Returns one line per library: what it added.
std::vector<std::string> load_plugins(Registry& registry, const std::vector<std::string>& libraries);

}  // namespace lcm_control::cm
