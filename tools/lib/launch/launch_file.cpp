#include "tools/lib/launch/launch_file.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "description/robot_model.hpp"

namespace fs = std::filesystem;

namespace lcm_control::tools {

std::string read_launch_text(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw ModelError(fmt::format("{}: launch file not found", path));
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

YAML::Node read_yaml_map(const std::string& path, const std::string& expected) {
  const std::string text = read_launch_text(path);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ModelError(fmt::format("{}:{}: malformed YAML: {}", path, e.mark.line + 1, e.msg));
  }
  if (!root.IsMap()) throw ModelError(fmt::format("{}: expected a map of {}", path, expected));
  return root;
}

std::string absolute_from(const std::string& p, const std::string& base_dir) {
  if (p.empty()) return p;
  fs::path f(p);
  if (f.is_relative()) f = fs::path(base_dir) / f;
  return fs::weakly_canonical(f).string();
}

std::vector<std::string> robot_names(int n) {
  std::vector<std::string> v;
  for (int i = 0; i < n; ++i) v.push_back("r" + std::to_string(i));
  return v;
}

std::string check_cpu(const std::string& cpu) {
  if (cpu == "auto" || cpu == "none") return "";
  if (!cpu.empty() && cpu.size() < 5 && cpu.find_first_not_of("0123456789") == std::string::npos) return "";
  return "must be auto (lockstep: sim_server and controller_manager on the least busy CPU), none, or a CPU number, "
         "not '" + cpu + "'";
}

LaunchPlan read_launch_file(const std::string& path, const std::vector<std::string>& package_path,
                            const std::vector<std::pair<std::string, std::string>>& args,
                            const std::set<std::string>& embedding_keys) {
  const std::string text = read_launch_text(path);
  const auto first = text.find_first_not_of(" \t\r\n");
  LaunchPlan plan = first != std::string::npos && text[first] == '<' ? read_ros_launch(path, package_path, args)
                                                                    : read_launch_yaml(path, package_path, embedding_keys);
  std::vector<std::string> problems;
  std::error_code ec;
  // No config: the URDF's gz_ros2_control plugin may name it (launcher.cpp).
  std::vector<std::pair<std::string, std::string>> files{{"URDF", plan.urdf}};
  for (const auto& c : plan.configs) files.emplace_back("ros_control YAML", c);
  for (const auto& [what, file] : files)
    if (!file.empty() && !fs::is_regular_file(file, ec)) problems.push_back(fmt::format("{}: the {} {} does not exist", path, what, file));
  if (!problems.empty()) throw ModelError(problems);
  return plan;
}

}  // namespace lcm_control::tools
