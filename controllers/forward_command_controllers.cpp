// The forwarding controllers: `<name>/command` goes to the joint(s) as is.
// One joint (`joint`, float64_t): position_controllers/JointPositionController,
// velocity_controllers/JointVelocityController, effort_controllers/JointEffortController.
// A group (`joints`, float64_array_t, one value per joint, wrong size dropped
// and counted): the three JointGroup*Controller types.
// ROS 2: forward_command_controller/ForwardCommandController (`joints`, the
// interface from `interface_name`) and MultiInterfaceForwardCommandController
// (`joint`, `interface_names`: one of them here, as the hardware takes one
// command per joint); the JointGroup names take ROS 2's `interface_name` too.
// On start a position command holds the current position; velocity and effort start at 0.
#include <fmt/format.h>

#include "controllers/factories.hpp"

namespace lcm_control::cm {

namespace {

// The interface a ROS 2 forward controller names in `key` (interface_name, interface_names).
Interface interface_named(Params& p, const std::string& key) {
  std::vector<std::string> names;
  if (key == "interface_names") {
    names = p.strings(key);
    if (names.size() != 1)
      throw p.error(key, fmt::format("[{}]: give one interface here (position, velocity or effort): the hardware "
                                     "takes one command per joint",
                                     fmt::join(names, ", ")));
  } else {
    names = {p.string(key)};
  }
  const auto i = interface_of_quantity(names.front());
  if (!i) throw p.error(key, fmt::format("'{}' is not a joint command interface; use position, velocity or effort",
                                         names.front()));
  return *i;
}

class ForwardCommandController : public Controller {
 public:
  // No `iface`: the ROS 2 parameter `interface_key` names it.
  ForwardCommandController(std::optional<Interface> iface, bool group, std::string interface_key = "")
      : iface_(iface.value_or(Interface::Position)), group_(group), interface_key_(std::move(interface_key)) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    if (!interface_key_.empty()) {
      iface_ = interface_named(p, interface_key_);
    } else if (group_ && p.has("interface_name") && interface_named(p, "interface_name") != iface_) {
      throw p.error("interface_name", fmt::format("'{}' does not fit {}; leave it out or use {}",
                                                  p.string("interface_name"), ctx.type(), quantity_of(iface_)));
    }
    const std::vector<std::string> names = group_ ? p.strings("joints") : std::vector<std::string>{p.string("joint")};
    for (const auto& n : names) joints_.push_back(ctx.claim(n, iface_));
    commands_.assign(joints_.size(), 0.0);
    ctx.take_commands(group_, joints_.size(), [this](const double* v) {
      if (running_)
        for (size_t k = 0; k < joints_.size(); ++k) commands_[k] = v[k];
    });
  }

  void starting(const Time&) override {
    for (size_t k = 0; k < joints_.size(); ++k)
      commands_[k] = iface_ == Interface::Position ? joints_[k]->position : 0.0;
  }

  void update(const Time&, double) override {
    for (size_t k = 0; k < joints_.size(); ++k) joints_[k]->command = commands_[k];
  }

 private:
  Interface iface_;
  bool group_;
  std::string interface_key_;
  std::vector<JointData*> joints_;
  std::vector<double> commands_;
};

}  // namespace

ControllerType forward_command_controller(Interface command, bool group) {
  ControllerTypeInfo t;
  const char* quantity = "";
  switch (command) {
    case Interface::Position:
      t.name = group ? "position_controllers/JointGroupPositionController" : "position_controllers/JointPositionController";
      quantity = "position";
      break;
    case Interface::Velocity:
      t.name = group ? "velocity_controllers/JointGroupVelocityController" : "velocity_controllers/JointVelocityController";
      quantity = "velocity";
      break;
    case Interface::Effort:
      t.name = group ? "effort_controllers/JointGroupEffortController" : "effort_controllers/JointEffortController";
      quantity = "effort";
      break;
  }
  if (group) t.ros = RosVersion::Both;
  t.doc = fmt::format("the {} command of {} as it comes", quantity, group ? "each joint of `joints`" : "`joint`");
  t.claims = {command, {group ? "joints" : "joint"}, "", {}};
  t.command = {group ? "float64_array_t" : "float64_t", "command", group ? CommandInfo::kOnePerJoint : 1, quantity};
  if (group)
    t.parameters = {{"joints", "strings", "", "joints", "joints", "the joints, in the order of the command's values"},
                    {"interface_name", "string", quantity, "", "interface_name", "ROS 2: must be " + std::string(quantity)}};
  else
    t.parameters = {{"joint", "string", "", "joint", "", "the joint"}};
  return {t, [command, group](const std::string&) { return std::make_unique<ForwardCommandController>(command, group); }};
}

ControllerType ros2_forward_command_controller(bool multi_interface) {
  ControllerTypeInfo t;
  t.name = multi_interface ? "forward_command_controller/MultiInterfaceForwardCommandController"
                           : "forward_command_controller/ForwardCommandController";
  t.ros = RosVersion::Ros2;
  const std::string key = multi_interface ? "interface_names" : "interface_name";
  t.doc = multi_interface ? "the command of `joint` on the one interface `interface_names` lists, as it comes"
                          : "the command of each joint of `joints` on `interface_name`, as it comes";
  t.claims.joint_params = {multi_interface ? "joint" : "joints"};
  t.claims.interface_param = key;
  t.command = {multi_interface ? "float64_t" : "float64_array_t", "command", multi_interface ? 1 : CommandInfo::kOnePerJoint,
               ""};
  if (multi_interface)
    t.parameters = {{"joint", "string", "", "", "joint", "the joint"},
                    {key, "strings", "", "", key, "one of position, velocity, effort (the hardware takes one)"}};
  else
    t.parameters = {{"joints", "strings", "", "", "joints", "the joints, in the order of the command's values"},
                    {key, "string", "", "", key, "position, velocity or effort"}};
  return {t, [multi_interface, key](const std::string&) {
            return std::make_unique<ForwardCommandController>(std::nullopt, !multi_interface, key);
          }};
}

}  // namespace lcm_control::cm
