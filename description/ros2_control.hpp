// ROS 2 descriptions: the <ros2_control> blocks of a URDF (hardware plugin,
// per-joint command and state interfaces with min/max/initial_value, mimic
// joints, sensors, gpios, the ROS 2 <transmission> form) and the gz_ros2_control
// plugin tag, read with ros2_control's rules (hardware_interface's
// component_parser): every listed joint exists and moves; a mimic joint (URDF
// <mimic>, unless mimic="false") takes no command interface and mimics a joint
// of its own block; min/max merge with the URDF <limit>, the stricter winning.
// A block's joints with command interfaces become the model's actuators
// (TransmissionSpec: the first command interface is the default, reduction 1,
// offset 0 unless a <transmission> says otherwise); initial_value gives the
// start pose. Only simulated (gz/ign/gazebo) and mock hardware is accepted.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace tinyxml2 {
class XMLElement;
}

namespace lcm_control {

struct RobotModel;

using Ros2Params = std::vector<std::pair<std::string, std::string>>;  // <param name=...>value</param>, in order

// One <command_interface> or <state_interface>.
struct Ros2Interface {
  std::string name;       // "position", "velocity", "effort", "acceleration", "force.x", "vacuum", ...
  std::string data_type;  // the data_type attribute; "" means double
  std::optional<double> min, max, initial_value;
  Ros2Params params;      // every <param>, min/max/initial_value included, as written
};

// One <joint>, <sensor> or <gpio> of a block.
struct Ros2Component {
  std::string name;
  int line = 0;
  std::vector<Ros2Interface> command_interfaces, state_interfaces;
  Ros2Params params;
  bool mimic = false;  // joints: a mimic joint by ros2_control's rules (URDF <mimic>, mimic attribute not "false")

  const Ros2Interface* command_interface(const std::string& name) const;
  const Ros2Interface* state_interface(const std::string& name) const;
};

// <transmission> inside <ros2_control> (ROS 2 syntax).
struct Ros2Transmission {
  std::string name, plugin, joint, actuator;
  double reduction = 1, offset = 0;
};

enum class HardwareKind { Simulator, Mock };
const char* to_string(HardwareKind k);  // "simulator", "mock"

// One <ros2_control> block.
struct HardwareBlock {
  std::string name;
  std::string type;    // system | actuator | sensor
  std::string plugin;  // <hardware><plugin>, e.g. gz_ros2_control/GazeboSimSystem
  HardwareKind kind = HardwareKind::Simulator;
  int line = 0;
  Ros2Params params;   // <hardware><param>
  std::vector<Ros2Component> joints, sensors, gpios;
  std::vector<Ros2Transmission> transmissions;

  const Ros2Component* joint(const std::string& name) const;
};

// <gazebo><plugin filename="gz_ros2_control-system" | "libgazebo_ros2_control.so" | "libign_ros2_control-system.so">.
struct Ros2ControlPlugin {
  bool present = false;
  std::string filename, name;
  std::vector<std::string> parameters;  // <parameters> files (the controllers YAML), as written
  std::string ns;                       // <ros><namespace>
  std::string controller_manager_name;  // <controller_manager_name>
  bool hold_joints = true;              // <hold_joints>: an actuated joint nobody commands is held still
  // <position_proportional_gain>: gz's P gain on the position error; read and reported, not used (our position
  // interface is a servo, not gz's first-order velocity loop).
  std::optional<double> position_proportional_gain;
};

// The kind of hardware a <plugin> names, by what it is rather than a list of names: a Gazebo/Ignition/gz simulator
// system (gz_ros2_control's GazeboSimSystem and its aliases and vendors' forks: a class named GazeboSimSystem,
// IgnitionSystem or GazeboSystem, or with GzSystem in its name), mock hardware (a class named GenericSystem:
// mock_components', fake_components'), or ros2_control_demos' mock-like example hardware; nullopt for one that drives
// real hardware. `rule`, when given, receives which of these matched, for the note that says so.
std::optional<HardwareKind> hardware_kind(const std::string& plugin, std::string* rule = nullptr);
// ros2_control_demos' example hardware (ros2_control_demo_example_N/...): mock-like stand-ins that integrate their
// velocity commands, played as mock hardware with calculate_dynamics.
bool demo_hardware(const std::string& plugin);

// The <gpio> interfaces of every block, named "<gpio>/<interface>" as the hardware loop carries them: the state
// interfaces with their initial_value (0 when none; a bool's "true" 1), and the command interfaces.
struct GpioInterfaces {
  std::vector<std::string> states;
  std::vector<double> initial;
  std::vector<std::string> commands;
};
GpioInterfaces gpio_interfaces(const std::vector<HardwareBlock>& blocks);

// True when `robot` holds a <ros2_control> block.
bool has_ros2_control(const tinyxml2::XMLElement* robot);
// Reads every <ros2_control> block into model.ros2_control, model.transmissions (the actuators),
// model.initial_positions / initial_velocities and the joints' limits. Problems are appended to `problems`
// (file:line, block and joint named), findings to model.notes / model.warnings. model.joints must be read.
void read_ros2_control(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                       std::vector<std::string>& problems);
// Reads the gz_ros2_control / gazebo_ros2_control plugin tag into model.ros2_control_plugin. A <hold_joints> or
// <position_proportional_gain> that is not a bool / number is appended to `problems` (file:line named).
void read_ros2_control_plugin(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                              std::vector<std::string>& problems);

}  // namespace lcm_control
