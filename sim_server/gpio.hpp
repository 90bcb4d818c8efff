// The simulated <gpio> interfaces of the <ros2_control> blocks, as gz_ros2_control and mock hardware play them: a
// command interface echoes to the state interface of the same name; a state interface without one keeps its
// initial_value. States go out as hardware_state_t sensor values named "<gpio>/<interface>".
#pragma once

#include <string>
#include <vector>

#include "description/robot_model.hpp"
#include "lcm_control/hardware_command_t.hpp"

namespace lcm_control::sim {

class GpioBank {
 public:
  explicit GpioBank(const RobotModel& model);

  const std::vector<std::string>& names() const { return names_; }  // the state interfaces
  const std::vector<double>& values() const { return values_; }
  bool empty() const { return names_.empty(); }
  int commands() const { return int(commands_.size()); }  // the command interfaces
  // The commanded values of an accepted hardware_command_t (its gpio arrays checked), kept until commit() applies
  // them with the actuators' commands. Matching its names to ours is redone only when its list of names changes. A
  // command for an interface that is no command interface of ours is counted in unknown(). Real-time safe once the
  // list is bound.
  void stage(const hardware_command_t& command);
  void commit();
  // The command interfaces of <gpio> `gpio` ignore commands while held (their component is not active).
  void hold(const std::string& gpio, bool held);
  void reset();  // back to the initial values
  int64_t unknown() const { return unknown_; }

 private:
  std::vector<std::string> names_;
  std::vector<double> values_, initial_;
  std::vector<std::string> commands_;  // our command interfaces
  std::vector<int> echo_;              // per command interface: its state's index, -1 none
  std::vector<std::string> bound_;     // the command message's list as last bound
  std::vector<int> slot_;              // per entry of bound_: our command interface, -1 none
  std::vector<double> staged_;         // per command interface: the value to apply, NaN none
  std::vector<char> held_;             // per command interface
  int64_t unknown_ = 0;
};

}  // namespace lcm_control::sim
