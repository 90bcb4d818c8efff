#include "controller_manager/hardware_status.hpp"

#include <fmt/format.h>

namespace lcm_control::cm {

void HardwareStatus::seen(const hardware_state_t& s, int64_t now) {
  if (!any_ || s.step != step_ || s.session != session_) step_since_us_ = now;
  any_ = true;
  session_ = s.session;
  step_ = s.step;
  lockstep_ = s.lockstep;
  e_stop_ = s.e_stop;
  period_us_ = s.period_us;
  real_time_factor_ = s.real_time_factor;
  last_us_ = now;
  if (window_start_us_ < 0) window_start_us_ = now;
  ++in_window_;
}

void HardwareStatus::close_window(int64_t now) {
  if (window_start_us_ >= 0 && now > window_start_us_)
    measured_hz_ = static_cast<double>(in_window_) * 1e6 / static_cast<double>(now - window_start_us_);
  window_start_us_ = any_ ? now : -1;
  in_window_ = 0;
}

std::string HardwareStatus::describe(int64_t now, int64_t silence_us, const std::string& channel,
                                     const std::string& transport) const {
  if (!any_)
    return fmt::format("no hardware state received on '{}': is sim_server (or the robot's driver) running with this "
                       "namespace and {}? Controllers are not updated until it publishes",
                       channel, transport);
  const double age_s = static_cast<double>(now - last_us_) / 1e6;
  std::string rate = period_us_ > 0 ? fmt::format("{:g} Hz", 1e6 / period_us_) : std::string("period unknown");
  if (measured_hz_ >= 0) rate += fmt::format(" ({:.1f} measured)", measured_hz_);
  std::string text = fmt::format("session {:x}, {}, {}", session_, lockstep_ ? "lockstep" : "real time", rate);
  if (lockstep_) text += fmt::format(", {:.2f}x real time", real_time_factor_);
  text += fmt::format(", step {}, last state {:.3f} s ago", step_, age_s);
  if (e_stop_) text += "; e-stop engaged: the hardware holds still";
  if (last_us_ - step_since_us_ > silence_us && now - last_us_ <= silence_us)
    text += fmt::format("; step {} repeated for {:.1f} s: the hardware is paused (cmctl resume){}", step_,
                        static_cast<double>(last_us_ - step_since_us_) / 1e6,
                        lockstep_ ? " or waiting for a command" : "");
  if (now - last_us_ > silence_us)
    text += fmt::format("; SILENT for {:.1f} s: controllers are not updated until '{}' resumes", age_s, channel);
  return text;
}

}  // namespace lcm_control::cm
