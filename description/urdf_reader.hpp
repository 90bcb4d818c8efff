// Reading a URDF into the robot model: links (inertia, collision and visual
// geometry with meshes resolved), joints (limits, dynamics), the
// <transmission> tags that say which interface each joint takes, and the
// gazebo_ros_control plugin tag. Transmissions are taken as
// gazebo_ros_control takes them: one per joint, SimpleTransmission only;
// what cannot be used is skipped with one warning naming it.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

// Fills `model`; throws ModelError at once only when the file cannot be parsed at all, otherwise adds
// every problem to `problems` so that all are reported together.
void read_urdf(RobotModel& model, const std::string& urdf_path, const LoadOptions& options,
               std::vector<std::string>& problems);
// The same, throwing every problem found.
void load_urdf_into(RobotModel& model, const std::string& urdf_path, const LoadOptions& options);

}  // namespace lcm_control
