// ROS package lookup without ROS: `package://NAME/...` and `$(find NAME)` are
// searched in folders given by --package-path, else $LCM_CONTROL_PACKAGE_PATH
// and $ROS_PACKAGE_PATH.
#pragma once

#include <string>
#include <vector>

namespace lcm_control {

// Resolves `package://NAME/rest`, `file://...`, absolute and relative (to base_dir) paths.
// Returns "" when the file does not exist.
std::string resolve_resource(const std::string& uri, const std::string& base_dir,
                             const std::vector<std::string>& package_path);
// $LCM_CONTROL_PACKAGE_PATH then $ROS_PACKAGE_PATH, colon-separated.
std::vector<std::string> default_package_path();
// The folder holding the ROS package that `file` belongs to (the parent of the nearest folder above it with a
// package.xml): a workspace's src/ or an install's share/. "" if the file is in no package.
std::string enclosing_packages_dir(const std::string& file);
// What a robot file's package:// and $(find) search: `package_path` (default_package_path() when empty), then
// enclosing_packages_dir(file), so that the robot's own package and the packages beside it are found without
// --package-path.
std::vector<std::string> package_path_for(const std::string& file, const std::vector<std::string>& package_path);
// The folder of ROS package NAME on the path (`$(find NAME)`), "" if absent: DIR/NAME, DIR itself if
// its name is NAME, or one level deeper (a catkin workspace's src/).
std::string find_package_dir(const std::string& name, const std::vector<std::string>& package_path);

}  // namespace lcm_control
