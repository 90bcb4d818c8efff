// What a controller reads and writes, as the controller manager hands it out: a joint (or a reference interface
// another controller exports), a <gpio> interface, a simulated sensor. Plain data the loop fills from hardware/state
// and turns into hardware/command; a controller keeps the pointers its init() got and reads and writes them in
// update() without allocating.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "control/joint_limits.hpp"
#include "control/transmission.hpp"
#include "description/robot_model.hpp"

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

}  // namespace lcm_control::cm
