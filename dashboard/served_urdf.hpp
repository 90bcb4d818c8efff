// The robot file the dashboard serves to the page's 3D view: under its own name, or for a .xacro, the URDF it expands
// to, written once into a private folder.
#pragma once

#include <string>

#include "description/robot_file.hpp"

namespace lcm_control::dashboard {

// The name the page asks for: the file's own, or for a .xacro the URDF it expands to (robot.urdf.xacro -> robot.urdf).
std::string served_urdf_name(const std::string& urdf);

// A .xacro robot file expanded once into a private folder of its own, served in place of the file; removed on exit.
class ExpandedUrdf {
 public:
  ExpandedUrdf(const std::string& urdf, const LoadOptions& options);
  ~ExpandedUrdf();
  ExpandedUrdf(const ExpandedUrdf&) = delete;
  ExpandedUrdf& operator=(const ExpandedUrdf&) = delete;
  const std::string& path() const { return path_; }

 private:
  std::string dir_, path_;
};

}  // namespace lcm_control::dashboard
