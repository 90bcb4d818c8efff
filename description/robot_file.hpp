// The URDF text of the robot file a user names: read as it is, or, when its name says xacro (`.urdf.xacro`,
// `.xacro.urdf`), expanded by our own xacro first (its arguments from --xacro-arg / a launch file's `xacro_args:`,
// `$(find PKG)` through the package path), so every program takes a xacro wherever it takes a URDF.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"
#include "xacro/budget.hpp"

namespace lcm_control {

bool is_xacro_file(const std::string& path);

// Throws ModelError naming the file (for a xacro: the line, and the chain of macros and includes that led there).
// `files_read`, if given, receives every file read (for a xacro: `path`, then its includes and YAML files).
std::string read_robot_file(const std::string& path, const LoadOptions& options,
                            std::vector<std::string>* files_read = nullptr);
// `path` expanded as a xacro whatever its name (the xacro program's job), with its arguments
// (options.xacro_args), the package lookup every program uses and the expansion budget; `use`, if given, receives
// what the expansion built against that budget.
std::string expand_xacro(const std::string& path, const LoadOptions& options,
                         std::vector<std::string>* files_read = nullptr, xacro::BudgetUse* use = nullptr);
// The expansion budget in force: the defaults times options.xacro_budget, else times $LCM_CONTROL_XACRO_BUDGET.
// Throws ModelError for a variable that is not a positive number.
xacro::Budget xacro_budget(const LoadOptions& options);

}  // namespace lcm_control
