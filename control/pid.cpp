#include "control/pid.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

namespace lcm_control {

std::string check_gains(const PidGains& g) {
  for (auto [name, v] : {std::pair{"p", g.p}, {"i", g.i}, {"d", g.d}, {"i_clamp_min", g.i_clamp_min},
                         {"i_clamp_max", g.i_clamp_max}})
    if (!std::isfinite(v)) return fmt::format("{} is not a finite number", name);
  if (g.i_clamp_min > 0) return fmt::format("i_clamp_min {} must be <= 0", g.i_clamp_min);
  if (g.i_clamp_max < 0) return fmt::format("i_clamp_max {} must be >= 0", g.i_clamp_max);
  return "";
}

void Pid::reset() {
  i_error_ = 0;
  last_error_ = 0;
  last_error_dot_ = 0;
  have_last_error_ = false;
  applied_ = false;
  p_term_ = i_term_ = d_term_ = 0;
}

double Pid::compute(double error, double dt) {
  applied_ = false;
  if (dt <= 0 || !std::isfinite(error) || !std::isfinite(dt)) return 0;
  const double error_dot = have_last_error_ ? (error - last_error_) / dt : 0.0;
  last_error_ = error;
  have_last_error_ = true;
  return compute(error, error_dot, dt);
}

double Pid::compute(double error, double error_dot, double dt) {
  applied_ = false;
  if (dt <= 0 || !std::isfinite(error) || !std::isfinite(error_dot) || !std::isfinite(dt)) return 0;
  last_error_dot_ = error_dot;
  const PidGains& g = gains_;
  p_term_ = g.p * error;
  i_error_ += dt * error;
  if (g.antiwindup && g.i != 0) {
    const double a = g.i_clamp_min / g.i, b = g.i_clamp_max / g.i;
    i_error_ = std::clamp(i_error_, std::min(a, b), std::max(a, b));
  }
  i_term_ = g.i * i_error_;
  if (!g.antiwindup) i_term_ = std::clamp(i_term_, g.i_clamp_min, g.i_clamp_max);
  d_term_ = g.d * error_dot;
  const double u = p_term_ + i_term_ + d_term_;
  applied_ = std::isfinite(u);
  if (applied_) return u;
  reset();  // terms that overflow (gains near 1e308) give no output rather than Inf or NaN
  return 0;
}

}  // namespace lcm_control
