#include "controller_interface/controller.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "bus/messages.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"

namespace lcm_control::cm {

void ControllerContext::record_claim(const std::string& joint, Interface iface) {
  if (!self_) return;
  Claim& c = self_->claim_;
  if (!c.interface) c.joints.clear();  // joints it only read were listed while it claimed nothing
  if (!c.interface) c.interface = iface;
  c.joints.push_back(joint);
  c.interfaces.push_back(iface);
}

void ControllerContext::record_read(const std::string& listed_as) {
  if (self_ && !self_->claim_.interface) self_->claim_.joints.push_back(listed_as);
}

void ControllerContext::record_gpio(const std::string& name) {
  if (self_) self_->claim_.gpios.push_back(name);
}

void ControllerContext::record_use(int component, bool commands) {
  if (!self_ || component < 0) return;
  std::vector<int>& list = commands ? self_->uses_.commands : self_->uses_.reads;
  if (std::find(list.begin(), list.end(), component) == list.end()) list.push_back(component);
}

void ControllerContext::record_export(JointData* reference) {
  if (self_) self_->exported_.push_back(reference);
}

std::vector<std::string> ControllerContext::actuated_joints() const { return model_.actuated_joints(); }

void ControllerContext::take_commands(bool array, size_t width, std::function<void(const double* values)> set) {
  if (!self_) throw ControllerError(fmt::format("controller '{}': take_commands() outside init()", name_));
  Controller* c = self_;
  const std::string name = name_;
  auto bad = [c, name](const std::string& why) {
    if (c->dropped_++ % 100 == 0)
      spdlog::warn("{}: dropped a command: {} ({} dropped so far)", name, why, c->dropped_);
  };
  c->input_ = CommandInput{array, width, set};
  if (array) {
    endpoints_.subscribe<float64_array_t>(
        channel("command"),
        [bad, width, set](const float64_array_t& m) {
          if (static_cast<size_t>(m.size) != width) return bad(fmt::format("{} values for {} joints", m.size, width));
          const std::string why = check(m);
          if (!why.empty()) return bad(why);
          set(m.data.data());
        },
        bad);
  } else {
    endpoints_.subscribe<float64_t>(
        channel("command"),
        [bad, set](const float64_t& m) {
          if (!std::isfinite(m.data)) return bad("NaN or Inf");
          set(&m.data);
        },
        bad);
  }
}

}  // namespace lcm_control::cm
