#include "sim_server/gpio.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace lcm_control::sim {

GpioBank::GpioBank(const RobotModel& model) {
  const GpioInterfaces g = gpio_interfaces(model.ros2_control);
  names_ = g.states;
  initial_ = values_ = g.initial;
  commands_ = g.commands;
  for (const auto& c : commands_) {
    const auto it = std::find(names_.begin(), names_.end(), c);
    echo_.push_back(it == names_.end() ? -1 : int(it - names_.begin()));
  }
  staged_.assign(commands_.size(), std::numeric_limits<double>::quiet_NaN());
  held_.assign(commands_.size(), 0);
}

void GpioBank::hold(const std::string& gpio, bool held) {
  for (size_t c = 0; c < commands_.size(); ++c)
    if (commands_[c].size() > gpio.size() && commands_[c].compare(0, gpio.size(), gpio) == 0 &&
        commands_[c][gpio.size()] == '/')
      held_[c] = held;
}

void GpioBank::stage(const hardware_command_t& command) {
  const size_t n = size_t(command.num_gpio_commands);
  if (bound_.size() != n || !std::equal(bound_.begin(), bound_.end(), command.gpio_interface.begin())) {
    bound_.assign(command.gpio_interface.begin(), command.gpio_interface.begin() + long(n));
    slot_.assign(n, -1);
    for (size_t k = 0; k < n; ++k) {
      const auto it = std::find(commands_.begin(), commands_.end(), bound_[k]);
      if (it != commands_.end()) slot_[k] = int(it - commands_.begin());
    }
  }
  for (size_t k = 0; k < n; ++k) {
    if (slot_[k] < 0)
      ++unknown_;
    else if (!held_[size_t(slot_[k])])
      staged_[size_t(slot_[k])] = command.gpio_command[k];
  }
}

void GpioBank::commit() {
  for (size_t c = 0; c < staged_.size(); ++c) {
    if (std::isnan(staged_[c])) continue;
    if (echo_[c] >= 0) values_[size_t(echo_[c])] = staged_[c];
    staged_[c] = std::numeric_limits<double>::quiet_NaN();
  }
}

void GpioBank::reset() {
  values_ = initial_;
  std::fill(staged_.begin(), staged_.end(), std::numeric_limits<double>::quiet_NaN());
}

}  // namespace lcm_control::sim
