// The forwarding controllers: `<name>/command` goes to the joint(s) as is.
// One joint (`joint`, float64_t): position_controllers/JointPositionController,
// velocity_controllers/JointVelocityController, effort_controllers/JointEffortController.
// A group (`joints`, float64_array_t, one value per joint, wrong size dropped
// and counted): the three JointGroup*Controller types.
// On start a position command holds the current position; velocity and effort start at 0.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <cmath>

#include "common/messages.hpp"
#include "controller_manager/controllers/factories.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"

namespace lcm_control::cm {

namespace {

Interface interface_of(const std::string& type) {
  if (type.rfind("position_controllers/", 0) == 0) return Interface::Position;
  if (type.rfind("velocity_controllers/", 0) == 0) return Interface::Velocity;
  return Interface::Effort;
}

class ForwardCommandController : public Controller {
 public:
  ForwardCommandController(Interface iface, bool group) : iface_(iface), group_(group) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const std::vector<std::string> names = group_ ? p.strings("joints") : std::vector<std::string>{p.string("joint")};
    for (const auto& n : names) joints_.push_back(ctx.claim(n, iface_));
    commands_.assign(joints_.size(), 0.0);
    const std::string name = ctx.name();
    auto bad = [this, name](const std::string& why) {
      if (dropped_++ % 100 == 0) spdlog::warn("{}: dropped a command: {} ({} dropped so far)", name, why, dropped_);
    };
    if (group_) {
      ctx.endpoints().subscribe<float64_array_t>(
          ctx.channel("command"),
          [this, bad](const float64_array_t& m) {
            if (static_cast<size_t>(m.size) != joints_.size()) {
              bad(fmt::format("{} values for {} joints", m.size, joints_.size()));
              return;
            }
            const std::string why = check(m);
            if (!why.empty()) return bad(why);
            if (running_)
              for (size_t k = 0; k < joints_.size(); ++k) commands_[k] = m.data[k];
          },
          bad);
    } else {
      ctx.endpoints().subscribe<float64_t>(
          ctx.channel("command"),
          [this, bad](const float64_t& m) {
            if (!std::isfinite(m.data)) return bad("NaN or Inf");
            if (running_) commands_[0] = m.data;
          },
          bad);
    }
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

std::unique_ptr<Controller> make_forward_command_controller(const std::string& type) {
  return std::make_unique<ForwardCommandController>(interface_of(type), type.find("/JointGroup") != std::string::npos);
}

}  // namespace lcm_control::cm
