#include "controller_manager/plugins.hpp"

#include <dlfcn.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <filesystem>

#include "controller_interface/plugin.hpp"

namespace lcm_control::cm {

namespace fs = std::filesystem;

std::vector<std::string> plugin_libraries(const RobotModel& model) {
  std::vector<std::string> out;
  for (const auto& c : model.controllers) {
    const YAML::Node p = c.params["plugin"];
    if (!p) continue;
    const std::string key_path = (model.config_section.empty() ? c.name : model.config_section + "/" + c.name) + "/plugin";
    const std::string file = model.config_file_of(key_path);
    const fs::path base = fs::path(file).parent_path();
    const std::string key = fmt::format("{}: {}", file, key_path);
    if (!p.IsScalar() || p.as<std::string>().empty())
      throw ModelError(fmt::format("{}: give the path of a controller library (.so), relative to the YAML's folder",
                                   key));
    fs::path lib = p.as<std::string>();
    if (lib.is_relative()) lib = base / lib;
    std::error_code ec;
    if (!fs::is_regular_file(lib, ec))
      throw ModelError(fmt::format("{}: {} is not a file (build the library, or fix the path: it is relative to "
                                   "the YAML's folder)",
                                   key, lib.string()));
    const std::string path = fs::weakly_canonical(lib).string();
    if (std::find(out.begin(), out.end(), path) == out.end()) out.push_back(path);
  }
  return out;
}

namespace {

std::string abi_text(const PluginAbi& a) {
  return fmt::format("controller ABI {}, {} std::string, Controller {} bytes, ControllerContext {} bytes, JointData "
                     "{} bytes",
                     a.controller_abi, a.cxx11_string_abi ? "C++11" : "pre-C++11", a.controller_size, a.context_size,
                     a.joint_data_size);
}

}  // namespace

std::vector<std::string> load_plugins(Registry& registry, const std::vector<std::string>& libraries) {
  std::vector<std::string> lines;
  for (const auto& path : libraries) {
    // Local symbols: the library's own copy of lcm_control never stands in for ours, nor ours for its.
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw ModelError(fmt::format("{}: cannot load the controller library: {}", path, dlerror()));
    using AbiFn = PluginAbi (*)();
    using RegisterFn = void (*)(Registry&);
    auto abi = reinterpret_cast<AbiFn>(dlsym(handle, "lcm_control_plugin_abi"));
    auto reg = reinterpret_cast<RegisterFn>(dlsym(handle, "lcm_control_register_controllers"));
    if (!abi || !reg)
      throw ModelError(fmt::format("{}: not an lcm_control controller library (no lcm_control_plugin_abi / "
                                   "lcm_control_register_controllers): export its types with "
                                   "LCM_CONTROL_CONTROLLER_PLUGIN (controller_interface/plugin.hpp)",
                                   path));
    const PluginAbi theirs = abi(), ours = this_plugin_abi();
    if (!(theirs == ours))
      throw ModelError(fmt::format("{}: built against another controller interface ({}; this controller_manager: "
                                   "{}): rebuild it against this lcm_control",
                                   path, abi_text(theirs), abi_text(ours)));
    Registry added;
    reg(added);
    const std::vector<std::string> types = added.types();
    if (types.empty()) throw ModelError(fmt::format("{}: registers no controller type", path));
    for (const auto& t : types)
      if (registry.has(t))
        throw ModelError(fmt::format("{}: registers '{}', which is already a controller type here: give yours a "
                                     "name of its own (my_controllers/...)",
                                     path, t));
    registry.merge(std::move(added));
    lines.push_back(fmt::format("controller library {}: {}", path, fmt::join(types, ", ")));
  }
  return lines;
}

}  // namespace lcm_control::cm
