// A start pose: joint positions by joint name (rad or m, joint space), given as
// JOINT=VALUE like spawn_model's -J; sim_server starts and resets there.
#pragma once

#include <map>
#include <string>
#include <utility>

namespace lcm_control {

// Joints not named start at 0 (clamped into their limits).
using InitialPositions = std::map<std::string, double>;

// "JOINT=VALUE" (or JOINT:=VALUE); throws std::invalid_argument naming what is wrong.
std::pair<std::string, double> parse_initial_position(const std::string& assignment);
// "" if parse_initial_position takes it, else its message (a CLI11 check).
std::string initial_position_problem(const std::string& assignment);

}  // namespace lcm_control
