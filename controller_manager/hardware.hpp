// The robot as controllers see it: one JointData per transmission (URDF
// transmission order), filled from hardware/state (actuator -> joint) and
// turned into hardware/command (joint -> actuator) as docs/hardware-protocol.md
// says. Binding a session (matching actuator names) is the only step that
// allocates; read(), enforce_soft_limits() and write() do not.
#pragma once

#include <cmath>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "controller_interface/handles.hpp"
#include "description/hardware_components.hpp"
#include "description/robot_model.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control::cm {

class Controller;

// A hardware component and its lifecycle state as the controller manager keeps it (ros2_control's resource manager).
struct ComponentData {
  HardwareComponent info;
  Lifecycle state = Lifecycle::Active;
  std::string error;        // why it last left active on an error ("" none)
  bool error_fresh = false;  // set by the loop when the error came; the manager logs it and clears this
  int64_t error_step = -1;
  // Its state interfaces can be read (inactive or active) / its commands act (active).
  static bool readable(Lifecycle s) { return s == Lifecycle::Inactive || s == Lifecycle::Active; }
  static bool commandable(Lifecycle s) { return s == Lifecycle::Active; }
  bool readable() const { return readable(state); }
  bool commandable() const { return commandable(state); }
};

class Hardware {
 public:
  explicit Hardware(const RobotModel& model);

  std::vector<JointData>& joints() { return joints_; }
  const std::vector<JointData>& joints() const { return joints_; }
  // A hardware joint, else a reference interface of that name.
  JointData* find(const std::string& joint);
  // Reference interfaces (chaining): the one named "<controller>/<dof>", made on its first export and kept (a
  // preceding controller holds its address); exported again, it takes the new interfaces and mirror.
  JointData& export_reference(const std::string& controller, const std::string& dof, std::vector<Interface> offered,
                              const JointData* mirror);
  JointData* reference(const std::string& name);
  // The exporter's reference interfaces are usable (loaded) or not (unloaded); their commands reset to 0.
  void set_references_live(const std::string& controller, bool live);
  std::vector<const JointData*> references_of(const std::string& controller) const;
  std::vector<SensorData>& sensors() { return sensors_; }
  const std::vector<SensorData>& sensors() const { return sensors_; }
  const SensorData* sensor(const std::string& name) const;
  std::vector<GpioData>& gpios() { return gpios_; }
  const std::vector<GpioData>& gpios() const { return gpios_; }
  GpioData* gpio(const std::string& name);  // "<gpio>/<interface>"; nullptr for none
  // In description order (hardware_components()), with the states the config starts them in.
  std::vector<ComponentData>& components() { return components_; }
  const std::vector<ComponentData>& components() const { return components_; }
  int component_index(const std::string& name) const;  // -1 for none; does not allocate

  // Matches the message's actuators to the transmissions by name; returns "" or
  // why this hardware does not fit the URDF. Sizes `command` for this session. Sensors match by
  // "<sensor>/<interface>"; one the hardware does not send stays NaN (missing_sensors() names them).
  std::string bind(const hardware_state_t& state, hardware_command_t& command);
  bool bound() const { return bound_; }
  int64_t session() const { return session_; }
  void unbind() { bound_ = false; }
  std::vector<std::string> missing_sensors() const;

  void read(const hardware_state_t& state);
  // The URDF's soft limits (<safety_controller>) on every owned joint's command, for the interface its controller
  // claimed, as joint_limits_interface's *SoftLimitsHandle (control/joint_limits.hpp). dt: this cycle's period (s).
  // `owner`: only the joints that controller owns.
  void enforce_soft_limits(double dt, const Controller* owner = nullptr);
  void reset_soft_limits();  // after a (re)start: position commands restart from the measured position
  // Also lists every component with its state when any is not active (hardware_command_t::component).
  void write(const hardware_state_t& state, hardware_command_t& command) const;

 private:
  std::vector<JointData> joints_;
  std::deque<JointData> references_;     // a deque: their addresses stay as more are exported
  std::vector<int> actuator_of_joint_;  // index in the hardware message (bind_actuators)
  std::vector<SensorData> sensors_;
  std::vector<int> sensor_slot_;        // per sensor value, in sensors_ order: its index in the message, -1 none
  std::vector<GpioData> gpios_;
  std::vector<ComponentData> components_;
  std::vector<int> gpio_slot_;          // per gpio, in gpios_ order: its state's index in the message's sensor values
  bool bound_ = false;
  int64_t session_ = 0;
};

}  // namespace lcm_control::cm
