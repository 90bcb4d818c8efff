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

#include "description/hardware_components.hpp"
#include "description/robot_model.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"

namespace lcm_control::cm {

class Controller;


struct JointData {
  std::string name;
  std::string actuator;
  const Joint* urdf = nullptr;
  SimpleTransmission map;
  std::vector<Interface> offered;  // from the transmission; offered.front() is what the hardware takes by default
  bool any_interface = false;      // a <ros2_control> joint: the hardware takes any of `offered`, switching to it
  bool continuous = false;
  double position = 0, velocity = 0, effort = 0;  // joint space, from the last read
  double command = 0;                             // joint space, written by the owning controller
  // Of an effort command, the N*m*s/rad (N*s/m) of -velocity it holds (a PID's D term), written with it: the
  // hardware may apply that part implicitly (hardware_command_t::damping).
  double damping = 0;
  const Controller* owner = nullptr;              // the running controller that claims it
  Interface owned_as = Interface::Position;       // on this interface (while owner is set)
  PositionSoftLimits soft_position;               // the previous position command, under soft limits
  int component = -1;                             // index in Hardware::components()
  // A reference interface of a chainable controller (ROS 2 chaining), "<controller>/<dof>": `command` is the
  // reference a preceding controller writes, the state is that of `mirror` (the joint the exporter commands), read
  // with the hardware's; never written to the hardware.
  std::string exported_by;                        // the exporting controller's name ("": a hardware joint)
  const JointData* mirror = nullptr;
  bool live = false;                              // its exporter is loaded (else a preceding controller is refused)
  // The hardware joint behind it (itself for a hardware joint; through every link of a chain).
  const JointData& hardware() const { return mirror ? mirror->hardware() : *this; }
};

// One <gpio> interface of the model, "<gpio>/<interface>": its state from the last hardware/state (NaN while the
// hardware sends none), and, for a command interface, the command its owning controller writes (NaN: none yet; only
// a finite command is sent).
struct GpioData {
  std::string name;
  bool has_state = false, has_command = false;  // a state / command interface of the <gpio>
  double state = NAN;
  double command = NAN;
  const Controller* owner = nullptr;  // the running controller that claims the command interface
  int component = -1;                 // index in Hardware::components()
};

// One simulated sensor of the model as controllers read it: its values in sensor_interfaces(kind) order from the
// last hardware/state, NaN while the hardware sends none of it.
struct SensorData {
  std::string name;
  SensorKind kind = SensorKind::Other;
  std::string frame_id;  // the sensor's frame_id, else its link
  std::vector<double> values;
  bool present = false;  // the bound hardware sends every value of it
  int component = -1;    // index in Hardware::components(); -1: a sensor outside every <ros2_control> block
};

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
  void enforce_soft_limits(double dt);
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
