#include "description/packages.hpp"

#include <cstdlib>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;

namespace lcm_control {

std::vector<std::string> default_package_path() {
  std::vector<std::string> out;
  for (const char* var : {"LCM_CONTROL_PACKAGE_PATH", "ROS_PACKAGE_PATH"}) {
    const char* v = std::getenv(var);
    if (!v) continue;
    std::stringstream ss(v);
    std::string item;
    while (std::getline(ss, item, ':'))
      if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::string enclosing_packages_dir(const std::string& file) {
  if (file.empty()) return "";
  std::error_code ec;
  const fs::path start = fs::absolute(file, ec).lexically_normal().parent_path();
  if (ec) return "";
  for (fs::path dir = start; dir.has_relative_path(); dir = dir.parent_path())
    if (fs::is_regular_file(dir / "package.xml", ec)) return dir.parent_path().string();
  return "";
}

std::vector<std::string> package_path_for(const std::string& file, const std::vector<std::string>& package_path) {
  std::vector<std::string> out = package_path.empty() ? default_package_path() : package_path;
  const std::string own = enclosing_packages_dir(file);
  if (!own.empty()) out.push_back(own);
  return out;
}

std::string find_package_dir(const std::string& name, const std::vector<std::string>& package_path) {
  std::error_code ec;
  for (const auto& dir : package_path) {
    const fs::path d(dir);
    if (d.filename() == name && fs::is_directory(d, ec)) return d.string();
    if (fs::is_directory(d / name, ec)) return (d / name).string();
    // One level deeper, as a catkin workspace's src/ holds packages in sub-folders.
    for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_directory(ec) && fs::is_directory(it->path() / name, ec)) return (it->path() / name).string();
  }
  return "";
}

std::string resolve_resource(const std::string& uri, const std::string& base_dir,
                             const std::vector<std::string>& package_path) {
  std::error_code ec;
  const std::string pkg = "package://", file = "file://";
  if (uri.rfind(pkg, 0) == 0) {
    const std::string rest = uri.substr(pkg.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos) return "";
    const std::string dir = find_package_dir(rest.substr(0, slash), package_path);
    if (dir.empty()) return "";
    const fs::path p = fs::path(dir) / rest.substr(slash + 1);
    return fs::exists(p, ec) ? fs::weakly_canonical(p, ec).string() : "";
  }
  fs::path p = uri.rfind(file, 0) == 0 ? fs::path(uri.substr(file.size())) : fs::path(uri);
  if (p.is_relative()) p = fs::path(base_dir) / p;
  return fs::exists(p, ec) ? fs::weakly_canonical(p, ec).string() : "";
}

}  // namespace lcm_control
