#include "controller_manager/services.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

namespace lcm_control::cm {

namespace {
const char* op_name(int op) {
  switch (op) {
    case cm_request_t::LIST:
      return "list";
    case cm_request_t::LIST_TYPES:
      return "list-types";
    case cm_request_t::LOAD:
      return "load";
    case cm_request_t::UNLOAD:
      return "unload";
    case cm_request_t::SWITCH:
      return "switch";
    case cm_request_t::RELOAD:
      return "reload";
    default:
      return "unknown";
  }
}
}  // namespace

std::string describe(const cm_request_t& r) {
  switch (r.op) {
    case cm_request_t::LOAD:
    case cm_request_t::UNLOAD:
      return fmt::format("{} [{}]", op_name(r.op), fmt::join(r.names, ", "));
    case cm_request_t::SWITCH:
      return fmt::format("switch start [{}] stop [{}] {}", fmt::join(r.start, ", "), fmt::join(r.stop, ", "),
                         r.strictness == cm_request_t::STRICT ? "STRICT" : "BEST_EFFORT");
    case cm_request_t::RELOAD:
      return r.force ? "reload (force)" : "reload";
    default:
      return op_name(r.op);
  }
}

Services::Services(ControllerManager& cm, Bus& bus)
    : cm_(cm), endpoints_(bus, Endpoints::On::Shared), pub_(endpoints_.publisher<cm_response_t>(bus.channel(channels::kCmResponse))) {
  const std::string channel = bus.channel(channels::kCmRequest);
  endpoints_.subscribe<cm_request_t>(
      channel, [this](const cm_request_t& r) { handle(r); },
      [this, channel](const std::string& why) {
        ++malformed_;
        cm_.count_dropped(1);
        cm_request_t r;
        r.request_id = -1;
        r.op = 0;
        const Reply reply{false, "malformed request: " + why + "; dropped (request_id unknown, answered as -1)"};
        log_.warn(reply.message);
        answer(r, reply);
      });
}

void Services::answer(const cm_request_t& req, const Reply& reply, bool with_types, bool with_hardware) {
  cm_response_t m{};  // every field zero: a field added to the type is never sent uninitialised
  m.utime = wall_us();
  m.request_id = req.request_id;
  m.op = req.op;
  m.ok = reply.ok;
  m.message = reply.message;
  m.controllers = cm_.list();
  m.num_controllers = static_cast<int32_t>(m.controllers.size());
  if (with_types) m.types = cm_.types();
  m.num_types = static_cast<int32_t>(m.types.size());
  const int64_t now = monotonic_us();
  m.hardware = with_hardware ? cm_.hardware_summary(now) : "";
  m.hardware_age_us = with_hardware ? cm_.hardware_age_us(now) : -1;
  m.ros2 = cm_.from_ros2();
  if (with_hardware) m.joints = cm_.interfaces();
  m.num_joints = static_cast<int32_t>(m.joints.size());
  pub_.publish(m);
  if (req.request_id < 0) return;
  const std::string line = fmt::format("request {}{}: {} -> {}: {}", req.request_id,
                                       req.client.empty() ? "" : " from " + clip(req.client), describe(req),
                                       reply.ok ? "ok" : "refused", reply.message);
  // A list changes nothing and dashboards ask for it every second: only --log-level debug shows it.
  const bool query = req.op == cm_request_t::LIST || req.op == cm_request_t::LIST_TYPES;
  if (query && reply.ok) log_.debug(line);
  else log_.info(line);
}

void Services::drain() {
  while (!deferred_.empty() && !cm_.busy()) {
    cm_request_t r = std::move(deferred_.front());
    deferred_.pop_front();
    handle(r);
  }
}

void Services::handle(const cm_request_t& r) {
  if (cm_.busy()) {
    deferred_.push_back(r);
    return;
  }
  auto names_ok = [&](const std::vector<std::string>& v, const char* field) -> std::string {
    if (v.size() > kMaxRequestNames)
      return fmt::format("malformed request: {} names in {}[]; at most {} in one request (docs/reliability.md, "
                         "\"Limits\")",
                         v.size(), field, kMaxRequestNames);
    for (size_t k = 0; k < v.size(); ++k)
      if (v[k].empty()) return fmt::format("malformed request: {}[{}] is an empty name", field, k);
    return "";
  };
  switch (r.op) {
    case cm_request_t::LIST:
      answer(r, {true, fmt::format("{} controller(s) loaded", cm_.list().size())}, false, true);
      return;
    case cm_request_t::LIST_TYPES:
      answer(r, {true, fmt::format("{} controller types", cm_.types().size())}, true);
      return;
    case cm_request_t::LOAD:
    case cm_request_t::UNLOAD: {
      if (r.names.empty())
        return answer(r, {false, fmt::format("malformed request: {} needs at least one controller name in names[]",
                                             op_name(r.op))});
      if (auto why = names_ok(r.names, "names"); !why.empty()) return answer(r, {false, why});
      answer(r, r.op == cm_request_t::LOAD ? cm_.load(r.names) : cm_.unload(r.names));
      return;
    }
    case cm_request_t::SWITCH: {
      for (auto [v, f] : {std::pair{&r.start, "start"}, {&r.stop, "stop"}})
        if (auto why = names_ok(*v, f); !why.empty()) return answer(r, {false, why});
      cm_request_t copy = r;
      cm_.switch_controllers(r.start, r.stop, r.strictness, [this, copy](const Reply& reply) {
        answer(copy, reply);
        drain();
      });
      return;
    }
    case cm_request_t::RELOAD: {
      cm_request_t copy = r;
      cm_.reload(r.force, [this, copy](const Reply& reply) {
        answer(copy, reply);
        drain();
      });
      return;
    }
    default:
      ++malformed_;
      answer(r, {false, fmt::format("malformed request: unknown op {}; valid ops are 1 LIST, 2 LIST_TYPES, 3 LOAD, "
                                    "4 UNLOAD, 5 SWITCH, 6 RELOAD",
                                    static_cast<int>(r.op))});
  }
}

}  // namespace lcm_control::cm
