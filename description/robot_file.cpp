#include "description/robot_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>

#include "description/input_file.hpp"
#include "description/packages.hpp"
#include "description/xacro/xacro.hpp"

namespace fs = std::filesystem;

namespace lcm_control {

bool is_xacro_file(const std::string& path) { return xacro::is_xacro(path); }

std::string read_robot_file(const std::string& path, const LoadOptions& options, std::vector<std::string>* files_read) {
  if (is_xacro_file(path)) return expand_xacro(path, options, files_read);
  std::string text = read_input_file(path, "URDF", "--urdf");
  if (files_read) files_read->push_back(path);
  return text;
}

std::string expand_xacro(const std::string& path, const LoadOptions& options, std::vector<std::string>* files_read) {
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
  try {
    xacro::Expansion e = xacro::expand_file(path, xo);
    if (files_read) files_read->insert(files_read->end(), e.files_read.begin(), e.files_read.end());
    return std::move(e.xml);
  } catch (const xacro::XacroError& e) {
    throw ModelError(e.what());
  }
}

}  // namespace lcm_control
