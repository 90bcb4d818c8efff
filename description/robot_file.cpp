#include "description/robot_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>

#include "description/input_file.hpp"
#include "description/packages.hpp"
#include "xacro/xacro.hpp"

namespace fs = std::filesystem;

namespace lcm_control {

bool is_xacro_file(const std::string& path) { return xacro::is_xacro(path); }

std::string read_robot_file(const std::string& path, const LoadOptions& options, std::vector<std::string>* files_read) {
  if (is_xacro_file(path)) return expand_xacro(path, options, files_read);
  std::string text = read_input_file(path, "URDF", "--urdf");
  if (files_read) files_read->push_back(path);
  return text;
}

xacro::Budget xacro_budget(const LoadOptions& options) {
  if (options.xacro_budget > 0) return xacro::Budget{}.scaled(options.xacro_budget);
  const char* env = std::getenv("LCM_CONTROL_XACRO_BUDGET");
  if (!env || !*env) return {};
  char* end = nullptr;
  const double factor = std::strtod(env, &end);
  if (*end != '\0' || !(factor > 0) || !std::isfinite(factor))
    throw ModelError(fmt::format("LCM_CONTROL_XACRO_BUDGET='{}' is not a factor: give a positive number such as 10 "
                                 "(every expansion budget times 10), or unset it",
                                 env));
  return xacro::Budget{}.scaled(factor);
}

std::string expand_xacro(const std::string& path, const LoadOptions& options, std::vector<std::string>* files_read,
                         xacro::BudgetUse* use) {
  read_input_file(path, "xacro", "");  // the checks every input file gets (exists, a regular file, its size)
  const std::vector<std::string> package_path = package_path_for(path, options.package_path);
  xacro::Options xo;
  xo.args = options.xacro_args;
  xo.find_package = [&package_path](const std::string& package) {
    const std::string dir = find_package_dir(package, package_path);
    return dir.empty() ? dir : fs::absolute(dir).lexically_normal().string();
  };
  xo.package_search_note =
      fmt::format("the package path is {}; give the folder that holds the package with --package-path DIR or "
                  "LCM_CONTROL_PACKAGE_PATH",
                  package_path.empty() ? "empty" : fmt::format("{}", fmt::join(package_path, ":")));
  xo.budget = xacro_budget(options);
  try {
    xacro::Expansion e = xacro::expand_file(path, xo);
    if (use) *use = e.budget_use;
    if (files_read) files_read->insert(files_read->end(), e.files_read.begin(), e.files_read.end());
    return std::move(e.xml);
  } catch (const xacro::XacroError& e) {
    throw ModelError(e.what());
  }
}

}  // namespace lcm_control
