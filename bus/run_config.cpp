#include "bus/run_config.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "description/robot_file.hpp"

namespace lcm_control {

std::string read_run_config(const RobotModel& model, const std::string& process, const std::vector<std::string>& argv,
                            run_config_t* out) {
  run_config_t m;
  m.version = LCM_CONTROL_VERSION;
  m.process = process;
  m.argv = argv;
  m.num_argv = static_cast<int32_t>(m.argv.size());
  m.robot_namespace = model.ns;
  m.urdf_path = model.urdf_path;
  try {
    m.urdf = read_robot_file(model.urdf_path, model.options);
    for (const std::string& path : model.config_paths) {
      std::ifstream in(path, std::ios::binary);
      std::ostringstream text;
      text << in.rdbuf();
      if (!in) return fmt::format("{} cannot be read any more", path);
      m.config_paths.push_back(path);
      m.configs.push_back(text.str());
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  m.num_configs = static_cast<int32_t>(m.configs.size());
  for (const auto& [name, value] : model.options.args) m.args.push_back(name + "=" + value);
  m.num_args = static_cast<int32_t>(m.args.size());
  *out = std::move(m);
  return "";
}

}  // namespace lcm_control
