// Cross-checks of a loaded robot model (URDF joints and limits, transmissions,
// pid_gains against the URDF): problems that stop the servers, warnings worth
// saying once, and hints doctor prints about things that are valid but often
// not what was meant.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"

namespace lcm_control {

// Adds every problem to `problems`, warnings to model.warnings and hints to model.hints.
void check_model(RobotModel& model, std::vector<std::string>& problems);
// The same, throwing ModelError listing every problem.
void validate(RobotModel& model);

// Joints Bullet takes, fixed ones too (sim_server's physics; mock hardware has no such limit): each is a link of its
// multibody, whose solver fills a Jacobian row over every degree of freedom for each active limit, motor and contact,
// so start-up time and memory grow with the square of the links (bench_scale: 1,000 joints about 4 s and 200 MB;
// 20,000 links on fixed joints took 75 s).
inline constexpr size_t kMaxSimulatedJoints = 1000;
// "" when Bullet takes the model, else why not, naming the file, the count and the limit (doctor, sim_server).
std::string simulation_size_problem(const RobotModel& model);

}  // namespace lcm_control
