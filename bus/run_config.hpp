// What a robot process was started with, as the run_config_t it publishes (controller_manager/config,
// sim_server/config) so that a recording of the run replays on its own: the URDF as it read it (a xacro's expansion),
// its configuration files' texts, the $(arg) values and its command line.
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"
#include "lcm_control/run_config_t.hpp"

namespace lcm_control {

// Fills `out` (utime left 0) from the model the process loaded; "" when done, else why a file could not be read
// again (it changed or went since start).
std::string read_run_config(const RobotModel& model, const std::string& process, const std::vector<std::string>& argv,
                            run_config_t* out);

}  // namespace lcm_control
