// Launch files for the launch program: our YAML format (config/turret_bot.launch.yaml, launch_yaml.cpp) and ROS
// launch XML such as the tutorial's gazebo_ros_control.launch (launch_ros_xml.cpp), both read into one LaunchPlan.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <string>
#include <vector>

#include "tools/lib/launch/launch_plan.hpp"

namespace lcm_control::tools {

// Reads either format (XML if the file starts with '<' after blanks, else YAML). `args`: NAME:=VALUE from the
// command line, which a ROS launch file's <arg default=> take as roslaunch does (its <include>s followed, each with
// its own <arg>s). Throws ModelError naming the file, line or key at fault.
// `embedding_keys`: the keys of a file that embeds a launch in YAML (a scenario's timeline and checks), left to it.
LaunchPlan read_launch_file(const std::string& path, const std::vector<std::string>& package_path,
                            const std::vector<std::pair<std::string, std::string>>& args = {},
                            const std::set<std::string>& embedding_keys = {});
LaunchPlan read_launch_yaml(const std::string& path, const std::vector<std::string>& package_path,
                            const std::set<std::string>& embedding_keys = {});
LaunchPlan read_ros_launch(const std::string& path, const std::vector<std::string>& package_path,
                           const std::vector<std::pair<std::string, std::string>>& args = {});

// What both readers share: the file's text (ModelError if it is not a file), a path made absolute from the launch
// file's folder, and the fix named for an $(arg) without a value.
std::string read_launch_text(const std::string& path);
// A YAML file's top-level map; ModelError naming the file and line when it is not YAML, or the file and `expected`
// when it is not a map.
YAML::Node read_yaml_map(const std::string& path, const std::string& expected);
std::string absolute_from(const std::string& p, const std::string& base_dir);
inline constexpr const char* kLaunchArgFix = "add <arg name=\"{0}\" default=\"...\"/> or pass {0}:=VALUE";

}  // namespace lcm_control::tools
