#include "controller_manager/gains.hpp"

#include "common/log.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <memory>

#include "common/messages.hpp"
#include "common/pid.hpp"

namespace lcm_control::cm {

void apply_gains_request(Controller& c, const std::string& name, const pid_gains_t& req, pid_gains_t& a) {
  a = pid_gains_t{};
  a.utime = wall_us();
  a.request_id = req.request_id;
  a.owner = name;
  a.joint = req.joint;
  a.query = req.query;
  const auto joints = c.pid_joints();
  std::string joint = req.joint;
  if (joint.empty() && joints.size() == 1) joint = joints.front();
  std::string all;
  for (const auto& j : joints) all += (all.empty() ? "" : ", ") + j;
  Pid* pid = joint.empty() ? nullptr : c.pid(joint);
  if (!pid) {
    a.ok = false;
    a.message = joint.empty() ? fmt::format("'{}' has PIDs for several joints ({}); say which in `joint`", name, all)
                              : fmt::format("'{}' has no PID for joint '{}' (its PIDs: {})", name, joint, all);
    return;
  }
  a.joint = joint;
  if (!req.owner.empty() && req.owner != name) {
    a.ok = false;
    a.message = fmt::format("request owner '{}' does not match controller '{}'", req.owner, name);
    set_gains(a, pid->gains());
    return;
  }
  if (req.query) {
    a.ok = true;
    a.message = fmt::format("gains of '{}' joint '{}'", name, joint);
    set_gains(a, pid->gains());
    return;
  }
  PidGains g = gains_of(req);
  const std::string why = check_gains(g);
  if (!why.empty()) {
    a.ok = false;
    a.message = fmt::format("refused gains for '{}' joint '{}': {}; gains unchanged", name, joint, why);
    set_gains(a, pid->gains());
    return;
  }
  pid->set_gains(g);
  a.ok = true;
  a.message = fmt::format("set gains of '{}' joint '{}': p {} i {} d {} i_clamp [{}, {}] antiwindup {}", name, joint,
                          g.p, g.i, g.d, g.i_clamp_min, g.i_clamp_max, g.antiwindup);
  set_gains(a, pid->gains());
}

void serve_gains(ControllerSlot& slot, Bus& bus) {
  Controller* c = slot.controller.get();
  const std::string name = slot.name;
  auto pub =
      std::make_shared<Publisher<pid_gains_t>>(slot.endpoints->publisher<pid_gains_t>(bus.channel(gains_channel(name))));
  auto answer = std::make_shared<pid_gains_t>();
  auto log = std::make_shared<BusLog>();
  slot.endpoints->subscribe<pid_gains_t>(
      bus.channel(gains_set_channel(name)),
      [c, name, pub, answer, log](const pid_gains_t& req) {
        apply_gains_request(*c, name, req, *answer);
        if (!req.query) log->info(answer->message);
        pub->publish(*answer);
      },
      [name, log](const std::string& why) { log->warn(name + " gains: " + why); });
}

}  // namespace lcm_control::cm
