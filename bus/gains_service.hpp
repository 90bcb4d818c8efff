// Run-time PID gains over LCM (ROS's dynamic reconfigure of pid gains): a pid_gains_t on `<owner>/gains/set` sets
// one joint's gains (checked), or with `query` only asks; the answer on `<owner>/gains` carries the gains in force.
// sim_server serves its pid_gains through it and the controller manager each controller's own PIDs, so both
// answer alike. The owner hands over a lookup of its PIDs; nothing here knows what owns them.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "bus/endpoints.hpp"
#include "control/pid.hpp"
#include "lcm_control/pid_gains_t.hpp"

namespace lcm_control {

// An owner's PIDs, looked up at each request (they may be rebuilt between requests: a sim reset).
struct PidLookup {
  std::function<std::vector<std::string>()> joints;  // the joints with a PID
  std::function<PidGains(const std::string& joint)> get;  // for a joint of joints()
  std::function<void(const std::string& joint, const PidGains&)> set;
  // Why `joint`, not one of joints(), has no PID, with what to do about it; "" (or none) for the plain refusal.
  std::function<std::string(const std::string& joint)> why_none;
};

// The answer to `request` for `owner`'s PIDs, set first when the request asks and the gains pass check_gains.
// `when` ends a set's message (" from step 9679"); `utime` stamps the answer.
pid_gains_t answer_gains(const std::string& owner, const PidLookup& pids, const pid_gains_t& request, int64_t utime,
                         const std::string& when = "");

// Answers every request on `<owner>/gains/set` (on `endpoints`) on `<owner>/gains`, both under the bus's namespace.
// `on_set` gets the message of each set applied (to log), `on_bad` the reason for bytes that are not a pid_gains_t.
struct GainsServiceHooks {
  std::function<int64_t()> utime;
  std::function<std::string()> when;  // may be empty
  std::function<void(const std::string&)> on_set, on_bad;
};
void serve_gains(Endpoints& endpoints, const Bus& bus, const std::string& owner, PidLookup pids,
                 GainsServiceHooks hooks);

}  // namespace lcm_control
