// The forwarding controllers: `<name>/command` goes to the joint(s) as is.
// One joint (`joint`, float64_t): position_controllers/JointPositionController,
// velocity_controllers/JointVelocityController, effort_controllers/JointEffortController.
// A group (`joints`, float64_array_t, one value per joint, wrong size dropped
// and counted): the three JointGroup*Controller types.
// On start a position command holds the current position; velocity and effort start at 0.
#include <fmt/format.h>

#include "controller_manager/controllers/factories.hpp"

namespace lcm_control::cm {

namespace {

class ForwardCommandController : public Controller {
 public:
  ForwardCommandController(Interface iface, bool group) : iface_(iface), group_(group) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
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
  if (group) t.ros2_names = {"forward_command_controller/ForwardCommandController"};
  t.doc = fmt::format("the {} command of {} as it comes", quantity, group ? "each joint of `joints`" : "`joint`");
  t.claims = {command, {group ? "joints" : "joint"}};
  t.command = {group ? "float64_array_t" : "float64_t", "command", group ? CommandInfo::kOnePerJoint : 1, quantity};
  if (group)
    t.parameters = {{"joints", "strings", "", "joints", "joints", "the joints, in the order of the command's values"}};
  else
    t.parameters = {{"joint", "string", "", "joint", "", "the joint"}};
  return {t, [command, group](const std::string&) { return std::make_unique<ForwardCommandController>(command, group); }};
}

}  // namespace lcm_control::cm
