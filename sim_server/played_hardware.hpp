// What the LCM side (sim_io, stepper) sees of the hardware sim_server plays,
// whichever plays it: Bullet's actuators (actuators.hpp) or mock hardware
// without physics (mock_hardware.hpp). Per actuator, in transmission order and
// actuator units: its name, the mode it takes now, its state; commands, hold,
// e-stop and PID gains. Every call is real-time safe.
#pragma once

#include <cstdint>
#include <string>

#include "control/pid.hpp"

namespace lcm_control::sim {

class PlayedHardware {
 public:
  virtual ~PlayedHardware() = default;

  virtual int size() const = 0;
  virtual const std::string& name(int i) const = 0;
  virtual const std::string& joint(int i) const = 0;
  int find_joint(const std::string& joint) const;  // -1 if no actuator drives it
  // The mode in use (hardware_command_t::MODE_*): the one last commanded, else the joint's first interface.
  virtual int8_t wire_mode(int i) const = 0;
  // True when the actuator takes commands in `wire_mode` (any interface its joint offers).
  virtual bool offers(int i, int8_t wire_mode) const = 0;
  // How the actuator plays its current mode, for messages ("position direct", "mock position", ...).
  virtual const char* mode_name(int i) const = 0;

  // A command in actuator units; MODE_NONE holds. A mode the joint does not offer holds too and returns false.
  // damping: of an effort command, the part -damping * velocity it holds (hardware_command_t::damping), which the
  // hardware may apply from the velocity at the end of the step instead.
  virtual bool set_command(int i, int8_t wire_mode, double value, double damping = 0) = 0;
  // Watchdog or lost controller: every actuator holds while set.
  virtual void set_hold_all(bool hold) = 0;
  virtual bool hold_all() const = 0;
  // Position actuators latch their position when it engages; velocity and effort get 0.
  virtual void set_e_stop(bool engaged) = 0;
  virtual bool e_stop() const = 0;

  virtual bool has_pid(int i) const = 0;
  virtual const PidGains& gains(int i) const = 0;
  virtual bool set_gains(int i, const PidGains& g) = 0;  // false without a PID

  // State after the last step, in actuator units.
  virtual double position(int i) const = 0;
  virtual double velocity(int i) const = 0;
  virtual double effort(int i) const = 0;
};

inline int PlayedHardware::find_joint(const std::string& joint_name) const {
  for (int i = 0; i < size(); ++i)
    if (joint(i) == joint_name) return i;
  return -1;
}

}  // namespace lcm_control::sim
