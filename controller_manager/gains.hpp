// Run-time gains of a controller's own PIDs (dynamic reconfigure): requests on
// `<controller>/gains/set`, answers with the gains in force on
// `<controller>/gains` (pid_gains_t, the type sim_server uses for its pid_gains).
#pragma once

#include "common/bus.hpp"
#include "controller_manager/loop.hpp"
#include "lcm_control/pid_gains_t.hpp"

namespace lcm_control::cm {

// Applies (or, with query, only reports) one request to `controller`; fills `answer`.
void apply_gains_request(Controller& controller, const std::string& name, const pid_gains_t& request,
                         pid_gains_t& answer);

// Subscribes the slot's port to its gains channel.
void serve_gains(ControllerSlot& slot, Bus& bus);

}  // namespace lcm_control::cm
