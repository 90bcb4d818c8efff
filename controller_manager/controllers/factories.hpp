// Factories of the built-in controller families, one per file in controllers/: a family's factory takes what
// distinguishes its types (the interface, one joint or a group), and registry.cpp names each type once.
#pragma once

#include <memory>
#include <string>

#include "controller_manager/controller.hpp"
#include "controller_manager/registry.hpp"

namespace lcm_control::cm {

std::unique_ptr<Controller> make_joint_state_controller(const std::string& type);
std::unique_ptr<Controller> make_diff_drive_controller(const std::string& type);
// `command` on one joint (a float64_t) or, with `group`, on `joints` (a float64_array_t).
Factory forward_command_controller(Interface command, bool group);
// A PID from a position or a velocity set point to the `out` command of one joint.
enum class PidTarget { Position, Velocity };
Factory pid_controller(Interface out, PidTarget target);
Factory group_position_pid_controller();  // effort_controllers/JointGroupPositionController
Factory joint_trajectory_controller(Interface command);

}  // namespace lcm_control::cm
