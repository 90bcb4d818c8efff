// Checks for LCM messages before they are used or sent: LCM does not verify
// that array-length fields match the arrays (a mismatch crashes the encoder),
// and a NaN must never reach the robot.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "control/pid.hpp"

namespace lcm_control {

inline bool all_finite(const std::vector<double>& v) {
  for (double x : v)
    if (!std::isfinite(x)) return false;
  return true;
}

// "" if the message is consistent, else what is wrong.
std::string check(const joint_state_t& m);
std::string check(const hardware_state_t& m);
std::string check(const hardware_command_t& m);
std::string check(const float64_array_t& m);

// Sizes every array to n and sets the count field (a hardware state's sensor values and errors and a command's GPIO
// commands and components keep theirs, counted).
void resize(joint_state_t& m, int n);
void resize(hardware_state_t& m, int n);
void resize(hardware_command_t& m, int n);

// A controller-manager request with its array counts set (request_id, client and utime are the sender's).
cm_request_t cm_request(int8_t op, std::vector<std::string> names = {}, std::vector<std::string> start = {},
                        std::vector<std::string> stop = {}, int8_t strictness = cm_request_t::STRICT);

// PID gains between the wire (pid_gains_t) and the PID.
PidGains gains_of(const pid_gains_t& m);
void set_gains(pid_gains_t& m, const PidGains& g);

}  // namespace lcm_control
