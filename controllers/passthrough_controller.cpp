// ros2_control_demos' passthrough_controller/PassthroughController (its example 12, the chaining demo): each entry of
// `interfaces`, "<joint or reference interface>/<interface>", is a command interface it writes and, under its own
// name, a reference interface it exports ("<name>/<joint>" on that interface), so that controllers chain through it
// level by level. What it writes is the reference a preceding controller wrote (chained mode), else its own
// `<name>/command` (float64_array_t, one value per entry); NaN until either comes, and then nothing is written.
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "controllers/factories.hpp"

namespace lcm_control::cm {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

class PassthroughController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const std::vector<std::string> entries = p.strings("interfaces");
    if (entries.empty()) throw p.error("interfaces", "give at least one \"<joint>/<interface>\"");
    for (const std::string& e : entries) {
      const size_t slash = e.rfind('/');
      const auto iface = slash == std::string::npos ? std::nullopt : interface_of_quantity(e.substr(slash + 1));
      if (!iface)
        throw p.error("interfaces", fmt::format("'{}': expected \"<joint>/<interface>\" with position, velocity or "
                                                "effort as the interface",
                                                e));
      const std::string joint = e.substr(0, slash);
      JointData* out = ctx.claim(joint, *iface);
      out_.push_back(out);
      refs_.push_back(ctx.export_reference(joint, {*iface}, out));
    }
    own_.assign(out_.size(), kNaN);
    ctx.take_commands(true, out_.size(), [this](const double* v) {
      if (!running_ || chained_mode()) return;
      for (size_t k = 0; k < own_.size(); ++k) own_[k] = v[k];
    });
  }

  void starting(const Time&) override {
    std::fill(own_.begin(), own_.end(), kNaN);
    for (JointData* r : refs_) r->command = kNaN;
  }

  void update(const Time&, double) override {
    for (size_t k = 0; k < out_.size(); ++k) {
      const double v = chained_mode() ? refs_[k]->command : own_[k];
      if (std::isfinite(v)) out_[k]->command = v;
    }
  }

 private:
  std::vector<JointData*> out_, refs_;
  std::vector<double> own_;
};

}  // namespace

ControllerType passthrough_controller() {
  ControllerTypeInfo t;
  t.name = "passthrough_controller/PassthroughController";
  t.ros = RosVersion::Ros2;
  t.chainable = true;
  t.references = "<name>/<joint> for each entry of interfaces, on that entry's interface";
  t.doc = "ros2_control_demos' chaining example: forwards references (chained) or <name>/command to `interfaces`, "
          "each also a reference interface <name>/<joint> of its own";
  t.claims.joint_params = {"interfaces"};  // "<joint>/<interface>" entries: each names its joint and interface
  t.claims.interface_param = "interfaces";
  t.command = {"float64_array_t", "command", CommandInfo::kOnePerJoint, ""};
  t.parameters = {ros2_parameter("interfaces", "strings", "",
                                 "\"<joint>/<interface>\" entries: the command interfaces it writes (a joint's, or "
                                 "another controller's reference interfaces) and exports again under its name")};
  return {t, [](const std::string&) { return std::make_unique<PassthroughController>(); }};
}

}  // namespace lcm_control::cm
