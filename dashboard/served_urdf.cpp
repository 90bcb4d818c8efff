#include "dashboard/served_urdf.hpp"

#include <fmt/format.h>
#include <stdlib.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace lcm_control::dashboard {

namespace fs = std::filesystem;

std::string served_urdf_name(const std::string& urdf) {
  const std::string name = fs::path(urdf).filename().string();
  if (!is_xacro_file(urdf)) return name;
  std::string stem = name;
  for (const char* ext : {".urdf.xacro", ".xacro.urdf", ".xacro"})
    if (stem.size() > std::strlen(ext) && stem.compare(stem.size() - std::strlen(ext), std::string::npos, ext) == 0) {
      stem.resize(stem.size() - std::strlen(ext));
      break;
    }
  return stem + ".urdf";
}

ExpandedUrdf::ExpandedUrdf(const std::string& urdf, const LoadOptions& options) {
  std::string dir = (fs::temp_directory_path() / "lcm_control_dashboard_XXXXXX").string();
  if (!::mkdtemp(dir.data())) throw std::runtime_error(fmt::format("cannot make a folder in {}", dir));
  dir_ = dir;
  path_ = (fs::path(dir_) / served_urdf_name(urdf)).string();
  std::FILE* f = std::fopen(path_.c_str(), "w");
  const std::string xml = read_robot_file(urdf, options);
  if (!f || std::fwrite(xml.data(), 1, xml.size(), f) != xml.size() || std::fclose(f) != 0)
    throw std::runtime_error(fmt::format("cannot write the expanded URDF {}", path_));
}

ExpandedUrdf::~ExpandedUrdf() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

}  // namespace lcm_control::dashboard
