// Run-time gains of a controller's own PIDs (dynamic reconfigure): common/gains_service on `<controller>/gains/set`
// and `<controller>/gains`, the service sim_server runs for its pid_gains.
#pragma once

#include "bus/bus.hpp"
#include "bus/gains_service.hpp"
#include "controller_manager/loop.hpp"

namespace lcm_control::cm {

// The controller's PIDs (Controller::pid_joints(), pid()) for the gains service.
PidLookup pid_lookup(Controller& controller);

// Serves the slot's gains channels through its endpoints.
void serve_gains(ControllerSlot& slot, Bus& bus);

}  // namespace lcm_control::cm
