// ROS 2's PID gains of one joint (control_toolbox's keys, under a controller's `gains.<joint>`), as the ROS 2
// controllers here read them: p, i, d default 0, the integral unclamped unless i_clamp* say so, u_clamp_* clamp the
// output, and one feed-forward key of the controller's (PidController: feedforward_gain; JointTrajectoryController:
// ff_velocity_scale). Keys ROS 2 has and this does not implement are accepted (antiwindup strategies with a note).
#pragma once

#include <limits>
#include <string>
#include <vector>
#include <yaml-cpp/yaml.h>

#include "control/pid.hpp"

namespace lcm_control::cm {

struct Ros2Gains {
  PidGains pid;
  double feedforward = 0;
  double u_min = -std::numeric_limits<double>::infinity(), u_max = std::numeric_limits<double>::infinity();
  bool wraparound = false;  // angle_wraparound
};

// Throws ControllerError naming `where` and the key for an unknown key or a bad value; notes what is not implemented.
Ros2Gains read_ros2_gains(const YAML::Node& node, const std::string& where, const std::string& feedforward_key,
                          std::vector<std::string>& notes);

}  // namespace lcm_control::cm
