#include "controller_manager/gains.hpp"

#include <memory>

#include "rt/log.hpp"

namespace lcm_control::cm {

PidLookup pid_lookup(Controller& c) {
  PidLookup l;
  l.joints = [&c] { return c.pid_joints(); };
  l.get = [&c](const std::string& joint) { return c.pid(joint)->gains(); };
  l.set = [&c](const std::string& joint, const PidGains& g) { c.pid(joint)->set_gains(g); };
  return l;
}

void serve_gains(ControllerSlot& slot, Bus& bus) {
  auto log = std::make_shared<BusLog>();
  GainsServiceHooks hooks;
  hooks.on_set = [log](const std::string& message) { log->info(message); };
  hooks.on_bad = [log](const std::string& why) { log->warn(why); };
  lcm_control::serve_gains(*slot.endpoints, bus, slot.name, pid_lookup(*slot.controller), std::move(hooks));
}

}  // namespace lcm_control::cm
