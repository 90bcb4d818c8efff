// Factories of the built-in controller families, one per file in controllers/.
#pragma once

#include <memory>
#include <string>

#include "controller_manager/controller.hpp"

namespace lcm_control::cm {

std::unique_ptr<Controller> make_joint_state_controller(const std::string& type);
std::unique_ptr<Controller> make_forward_command_controller(const std::string& type);
std::unique_ptr<Controller> make_pid_controller(const std::string& type);
std::unique_ptr<Controller> make_joint_trajectory_controller(const std::string& type);
std::unique_ptr<Controller> make_diff_drive_controller(const std::string& type);

}  // namespace lcm_control::cm
