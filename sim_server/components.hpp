// The hardware components as the simulator plays their lifecycle (docs/hardware-protocol.md, "Hardware
// components"): the controller manager's commands say which are not active, and those ignore their actuators' and
// GPIOs' commands and hold their joints (brakes, as an uncommanded actuator); a component failed through the
// FAIL_COMPONENT test hook reports its error in every hardware_state_t, holding too, until a command lists it as not
// active.
#pragma once

#include <string>
#include <vector>

#include "description/hardware_components.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control::sim {

class GpioBank;

class ComponentStates {
 public:
  explicit ComponentStates(const RobotModel& model);
  // The simulator's actuator names, in its order (holds() takes their index).
  void bind(const std::vector<std::string>& actuators);

  const std::vector<HardwareComponent>& components() const { return components_; }
  // The states an accepted command lists (none: every component active); acknowledges the errors of those it lists
  // as not active, and marks their GPIO command interfaces held in `gpio`. Returns one line per component whose
  // state changed, for the log ("" lines none). Does not allocate while the list of states stays the same.
  std::vector<std::string> take(const hardware_command_t& command, GpioBank& gpio);
  bool holds(int actuator) const { return size_t(actuator) < held_.size() && held_[size_t(actuator)] != 0; }
  Lifecycle state(size_t component) const { return states_[component]; }
  // Per actuator (bind()'s order): its component's index in components(), -1 none.
  const std::vector<int>& component_of() const { return component_of_; }

  // The FAIL_COMPONENT test hook; "" or why not (no such component).
  std::string fail(const std::string& component, const std::string& reason, GpioBank& gpio);
  // Writes the errors not yet acknowledged into `state` (its error arrays; none: empty) when they changed since the
  // last call: `state` is the one message the simulator publishes every step, so it keeps them meanwhile.
  void report(hardware_state_t& state);

 private:
  void update_holds(GpioBank& gpio);

  std::vector<HardwareComponent> components_;
  std::vector<int> component_of_;   // per actuator: its component, -1 none
  std::vector<Lifecycle> states_;   // as the last command says
  std::vector<std::string> errors_;  // per component: the error not yet acknowledged, "" none
  std::vector<char> held_;          // per actuator
  bool any_error_ = false;
  bool errors_changed_ = true;  // since the last report()
};

}  // namespace lcm_control::sim
