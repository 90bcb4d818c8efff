// switch_controller's decision, as ros_control makes it (pure, no side effects):
// STRICT refuses unknown names, stopping a controller that is not running and
// starting one that is; BEST_EFFORT drops those entries (and says so); a name
// in both lists and a claim conflict in the post-switch set are always refused, as is (ROS 2 chaining) a running
// controller whose followers would not all run after the switch, naming both.
#pragma once

#include <string>
#include <vector>

#include "controller_interface/controller.hpp"

namespace lcm_control::cm {

struct LoadedController {
  std::string name;
  std::string state;  // "initialized", "running", "stopped"
  const Claim* claim = nullptr;
  std::vector<std::string> follows;  // chaining: the controllers whose reference interfaces it claims
};

struct SwitchPlan {
  bool ok = false;
  std::string message;    // why it was refused, or what will happen
  std::vector<int> stop;  // indices into the loaded list, load order
  std::vector<int> start;
  std::vector<std::string> notes;  // entries BEST_EFFORT dropped, strictness fixes
  bool empty() const { return stop.empty() && start.empty(); }
};

// strictness: cm_request_t::BEST_EFFORT (1) or STRICT (2); 0 is BEST_EFFORT with a note.
SwitchPlan plan_switch(const std::vector<LoadedController>& loaded, const std::vector<std::string>& start,
                       const std::vector<std::string>& stop, int strictness);

}  // namespace lcm_control::cm
