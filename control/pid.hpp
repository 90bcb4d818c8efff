// PID with control_toolbox::Pid semantics (p*e + i*integral + d*de/dt, i_clamp,
// antiwindup), except that the first sample after a reset has no derivative kick.
// Real-time safe: no allocation, no locks.
#pragma once

#include <string>

namespace lcm_control {

struct PidGains {
  double p = 0, i = 0, d = 0;
  double i_clamp_min = 0, i_clamp_max = 0;  // i_clamp c gives [-|c|, |c|]; 0 means the I term is 0
  bool antiwindup = false;
};

// Checks gains a user typed: finite, i_clamp_min <= 0 <= i_clamp_max. Returns "" or the reason.
std::string check_gains(const PidGains& g);

class Pid {
 public:
  Pid() = default;
  explicit Pid(const PidGains& g) : gains_(g) {}

  void set_gains(const PidGains& g) { gains_ = g; }
  const PidGains& gains() const { return gains_; }

  // Forgets the integral and the last error; the next sample has no D term.
  void reset();

  // error = target - measured. de/dt is estimated from the previous error; 0 on the first sample. Always finite:
  // when the terms overflow (absurd gains) the output is 0 and the state is reset.
  double compute(double error, double dt);
  // With an explicit error derivative (e.g. -velocity for a constant target).
  double compute(double error, double error_dot, double dt);

  // The gains the last output applied to `error` and to `error_dot` (0 when it gave none: a reset, a bad sample, an
  // overflow). With error_dot = target rate - velocity, the output holds -applied_d() * velocity; with error = target
  // velocity - velocity, -applied_p() * velocity: the damping an effort command declares (hardware_command_t).
  double applied_p() const { return applied_ ? gains_.p : 0.0; }
  double applied_d() const { return applied_ ? gains_.d : 0.0; }
  double last_p_term() const { return p_term_; }
  double last_i_term() const { return i_term_; }
  double last_d_term() const { return d_term_; }
  double integral() const { return i_error_; }

 private:
  PidGains gains_;
  double i_error_ = 0, last_error_ = 0, last_error_dot_ = 0;
  bool have_last_error_ = false;
  bool applied_ = false;
  double p_term_ = 0, i_term_ = 0, d_term_ = 0;
};

}  // namespace lcm_control
