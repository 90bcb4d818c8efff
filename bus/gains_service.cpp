#include "bus/gains_service.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <memory>

#include "bus/messages.hpp"

namespace lcm_control {

pid_gains_t answer_gains(const std::string& owner, const PidLookup& pids, const pid_gains_t& req, int64_t utime,
                         const std::string& when) {
  pid_gains_t a{};
  a.utime = utime;
  a.request_id = req.request_id;
  a.owner = owner;
  a.joint = req.joint;
  a.query = req.query;
  const std::vector<std::string> joints = pids.joints();
  const std::string all = joints.empty() ? "none" : fmt::format("{}", fmt::join(joints, ", "));
  std::string joint = req.joint;
  if (joint.empty() && joints.size() == 1) joint = joints.front();
  if (joint.empty()) {
    a.message = fmt::format("'{}' has PIDs for several joints ({}); say which in `joint`", owner, all);
    return a;
  }
  if (std::find(joints.begin(), joints.end(), joint) == joints.end()) {
    const std::string why = pids.why_none ? pids.why_none(joint) : "";
    a.message = !why.empty() ? why : fmt::format("'{}' has no PID for joint '{}' (its PIDs: {})", owner, joint, all);
    return a;
  }
  a.joint = joint;
  set_gains(a, pids.get(joint));
  if (!req.owner.empty() && req.owner != owner) {
    a.message = fmt::format("request owner '{}' does not match '{}'", req.owner, owner);
    return a;
  }
  if (req.query) {
    a.ok = true;
    a.message = fmt::format("gains in force for '{}' joint '{}'", owner, joint);
    return a;
  }
  const PidGains g = gains_of(req);
  if (const std::string why = check_gains(g); !why.empty()) {
    a.message = fmt::format("refused gains for '{}' joint '{}': {}; gains unchanged", owner, joint, why);
    return a;
  }
  pids.set(joint, g);
  set_gains(a, pids.get(joint));
  a.ok = true;
  a.message = fmt::format("set gains of '{}' joint '{}': p {:g} i {:g} d {:g} i_clamp [{:g}, {:g}]{}{}", owner, joint,
                          g.p, g.i, g.d, g.i_clamp_min, g.i_clamp_max, g.antiwindup ? " antiwindup" : "", when);
  return a;
}

void serve_gains(Endpoints& endpoints, const Bus& bus, const std::string& owner, PidLookup pids,
                 GainsServiceHooks hooks) {
  auto pub = std::make_shared<Publisher<pid_gains_t>>(endpoints.publisher<pid_gains_t>(bus.channel(gains_channel(owner))));
  endpoints.subscribe<pid_gains_t>(
      bus.channel(gains_set_channel(owner)),
      [owner, pids = std::move(pids), hooks, pub](const pid_gains_t& req) {
        const pid_gains_t answer =
            answer_gains(owner, pids, req, hooks.utime ? hooks.utime() : wall_us(), hooks.when ? hooks.when() : "");
        if (!req.query && answer.ok && hooks.on_set) hooks.on_set(answer.message);
        pub->publish(answer);
      },
      [on_bad = hooks.on_bad, owner](const std::string& why) {
        if (on_bad) on_bad(owner + "/gains/set: " + why);
      });
}

}  // namespace lcm_control
