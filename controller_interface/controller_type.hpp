// What a controller type says about itself, declared next to its factory (a built-in's or a plugin's alike): the ROS
// names it answers to, the joints it claims, what it takes on its command channel, what it publishes, its parameters
// and the reference interfaces it exports. Plain data: the controller manager, doctor, `cmctl list` and list-types,
// the dashboard and send-trajectory read it instead of parsing type names.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "controller_interface/claims.hpp"
#include "description/robot_model.hpp"

namespace lcm_control::cm {

class Controller;

// The joints a type claims: on `interface`, the ones its parameters `joint_params` name ("joint", "joints",
// "left_wheel" and "right_wheel"). No interface: it reads joints and claims none, unless `interface_param` names
// the parameter that chooses it (ROS 2's `interface_name`, `command_interfaces`).
struct ClaimInfo {
  std::optional<Interface> interface;
  std::vector<std::string> joint_params;
  std::string interface_param;
  // Joints other parameters name, claimed on another interface (a steering drive's steering joints on position).
  struct Also {
    Interface interface;
    std::vector<std::string> joint_params;
  };
  std::vector<Also> also;
};

// What it takes on `<name>/<channel>`: a message type of lcmtypes/ ("float64_t", "float64_array_t",
// "joint_trajectory_t", "twist_t"; "" for nothing) and, for numbers, how many and what each one sets.
struct CommandInfo {
  static constexpr int kOnePerJoint = -1;
  std::string type;
  std::string channel = "command";
  int width = 0;         // numbers per message: 1, kOnePerJoint or a fixed count; 0 when the message is not numbers
  std::string quantity;  // "position", "velocity" or "effort": the set point each number is; "" when not numbers
                         // or when ClaimInfo::interface_param chooses it (then it is the claimed interface's)
};

// One YAML key. `ros1`, `ros2`: what ROS 1's and ROS 2's controller call it ("" when they have no such key); a key
// ROS has and this type does not read is listed with `implemented` false, to be named as such, not as a misspelling.
struct ParameterInfo {
  std::string name;
  std::string type;           // "number", "bool", "string", "strings" (a list of names), "map", "list"
  std::string default_value;  // as YAML; "" when required or worked out (the doc says how)
  std::string ros1, ros2;
  std::string doc;            // one line
  bool implemented = true;
};

// A parameter ROS 2 names and ROS 1 does not have.
inline ParameterInfo ros2_parameter(const char* name, const char* type, const char* default_value, const char* doc,
                                    bool implemented = true) {
  return ParameterInfo{name, type, default_value, "", name, doc, implemented};
}

// Whose class name a type's name is: ros_controllers' (ROS 1), ros2_controllers' (ROS 2) or both (the same name
// with either's parameters, e.g. diff_drive_controller/DiffDriveController).
enum class RosVersion { Ros1, Ros2, Both };
const char* to_string(RosVersion v);  // "ROS 1", "ROS 2", "ROS 1 and ROS 2"

struct ControllerTypeInfo {
  std::string name;  // the type name it is registered as (a ROS class name)
  RosVersion ros = RosVersion::Ros1;
  std::string doc;                      // one line
  ClaimInfo claims;
  CommandInfo command;
  std::vector<std::string> publishes;   // channels outside `<name>/` it publishes (e.g. joint_states)
  std::vector<ParameterInfo> parameters;
  // Chaining (ROS 2): a chainable type exports reference interfaces "<name>/<dof>" that preceding controllers claim
  // as joints (ControllerContext::export_reference refuses any other type); `references` says which, in one line.
  bool chainable = false;
  std::string references;
};

// Every key a YAML entry of the type may hold as ROS knows it (read here or not): the names and the ROS 1 and
// ROS 2 names of its parameters, in declaration order, each once.
std::vector<std::string> parameter_names(const ControllerTypeInfo& info);

// "" when what a controller of `info`'s type claimed after init() (`claim`, from its YAML entry `params`) is what
// its declaration says it claims (ClaimInfo: the joints its joint parameters name, on the declared interface), else
// the first claim the declaration does not cover. A type that declares nothing is not checked.
std::string undeclared_claim(const ControllerTypeInfo& info, const YAML::Node& params, const Claim& claim);

// Creates a controller of `type` (one factory may serve a family of types).
using Factory = std::function<std::unique_ptr<Controller>(const std::string& type)>;

// A type as registered: what it says about itself and how to make one.
struct ControllerType {
  ControllerTypeInfo info;
  Factory factory;
};

}  // namespace lcm_control::cm
