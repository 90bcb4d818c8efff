// my_controllers/SineController: moves one joint (position interface) along
// center + amplitude * sin(2 pi frequency t); without `center`, centred where
// the joint is when the controller starts. YAML:
//   sine_controller:
//     type: my_controllers/SineController
//     plugin: my_build/libmy_controllers.so   # relative to the YAML's folder
//     joint: j1
//     amplitude: 0.4                          # rad or m
//     frequency: 0.5                          # Hz, default 0.5
//     center: 0.5                             # optional
#include <cmath>
#include <memory>

#include "controller_interface/plugin.hpp"

namespace {

using namespace lcm_control::cm;

class SineController : public Controller {
 public:
  void init(ControllerContext& ctx) override {  // not real time: read parameters, claim joints
    joint_ = ctx.claim(ctx.params().string("joint"), lcm_control::Interface::Position);
    amplitude_ = ctx.params().number("amplitude");
    frequency_ = ctx.params().number("frequency", 0.5);
    if (frequency_ <= 0) throw ctx.params().error("frequency", "must be > 0 Hz");
    if (ctx.params().has("center")) center_ = ctx.params().number("center"), fixed_center_ = true;
  }
  void starting(const Time& now) override {  // real time from here on: no allocation, no logging
    start_s_ = now.seconds();
    if (!fixed_center_) center_ = joint_->position;
  }
  void update(const Time& now, double /*period*/) override {
    joint_->command = center_ + amplitude_ * std::sin(2 * M_PI * frequency_ * (now.seconds() - start_s_));
  }

 private:
  JointData* joint_ = nullptr;
  double amplitude_ = 0, frequency_ = 0, start_s_ = 0, center_ = 0;
  bool fixed_center_ = false;
};

// What the type says of itself, as a built-in type does: doctor names a misspelt key with the closest of these,
// `cmctl list-types` shows the doc line, `cmctl list` and the dashboard what it claims and takes.
ControllerType sine_controller() {
  ControllerTypeInfo t;
  t.name = "my_controllers/SineController";
  t.ros = RosVersion::Ros2;
  t.doc = "moves one joint along center + amplitude * sin(2 pi frequency t)";
  t.claims = {lcm_control::Interface::Position, {"joint"}};
  t.parameters = {ros2_parameter("joint", "string", "", "the joint, commanded in position"),
                  ros2_parameter("amplitude", "number", "", "rad or m"),
                  ros2_parameter("frequency", "number", "0.5", "Hz"),
                  ros2_parameter("center", "number", "", "rad or m; without it, where the joint is at start")};
  return {t, [](const std::string&) { return std::make_unique<SineController>(); }};
}

}  // namespace

LCM_CONTROL_CONTROLLER_PLUGIN([](Registry& r) { r.add(sine_controller()); })
