#include "controller_manager/services.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <limits>

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
    case cm_request_t::SET_COMPONENT_STATE:
      return "set-hardware-component-state";
    case cm_request_t::CONFIG:
      return "config";
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
    case cm_request_t::SET_COMPONENT_STATE:
      return fmt::format("set-hardware-component-state {} {}", r.names.empty() ? "" : r.names.front(),
                         lifecycle_label(r.component_state));
    default:
      return op_name(r.op);
  }
}

Services::Services(ControllerManager& cm, Bus& bus, int64_t slice_us)
    : cm_(cm),
      endpoints_(bus, Endpoints::On::Shared),
      pub_(endpoints_.publisher<cm_response_t>(bus.channel(channels::kCmResponse))),
      slice_us_(slice_us) {
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
  m.message = reply.message.size() > kMaxAnswerMessage ? clip(reply.message, kMaxAnswerMessage) : reply.message;
  if (with_types) m.types = cm_.types();
  m.num_types = static_cast<int32_t>(m.types.size());
  for (const std::string& t : m.types) m.type_docs.push_back(cm_.type_doc(t));
  const int64_t now = monotonic_us();
  m.hardware = with_hardware ? cm_.hardware_summary(now) : "";
  m.hardware_age_us = with_hardware ? cm_.hardware_age_us(now) : -1;
  m.ros2 = cm_.from_ros2();
  if (with_hardware) m.joints = cm_.interfaces();
  if (with_hardware || req.op == cm_request_t::SET_COMPONENT_STATE) m.components = cm_.components();
  m.num_components = static_cast<int32_t>(m.components.size());
  const size_t room = kMaxAnswerBytes - 256;  // 256: the note below
  size_t bytes = static_cast<size_t>(m.getEncodedSize());
  size_t joints = 0;
  for (; joints < m.joints.size(); ++joints) {
    bytes += static_cast<size_t>(m.joints[joints]._getEncodedSizeNoHash());
    if (bytes > room / 2) break;
  }
  const size_t all_joints = m.joints.size();
  m.joints.resize(joints);
  m.num_joints = static_cast<int32_t>(m.joints.size());
  bytes = static_cast<size_t>(m.getEncodedSize());
  m.controllers = cm_.list(bytes < room ? room - bytes : 0);
  m.num_controllers = static_cast<int32_t>(m.controllers.size());
  const size_t loaded = cm_.loaded();
  if (m.controllers.size() < loaded)
    m.message += fmt::format(" [{} of {} controllers listed, in load order: an answer is at most {} KB]",
                             m.controllers.size(), loaded, kMaxAnswerBytes / 1024);
  if (joints < all_joints)
    m.message += fmt::format(" [{} of {} joints listed: an answer is at most {} KB]", joints, all_joints,
                             kMaxAnswerBytes / 1024);
  pub_.publish(m);
  if (req.request_id < 0) return;
  const std::string line = fmt::format("request {}{}: {} -> {}: {}", req.request_id,
                                       req.client.empty() ? "" : " from " + clip(req.client), describe(req),
                                       reply.ok ? "ok" : "refused", reply.message);
  // A list changes nothing and dashboards ask for it every second: only --log-level debug shows it.
  const bool query =
      req.op == cm_request_t::LIST || req.op == cm_request_t::LIST_TYPES || req.op == cm_request_t::CONFIG;
  if (query && reply.ok) log_.debug(line);
  else log_.info(line);
}

void Services::handle(const cm_request_t& r) {
  queue_.push_back(r);
  if (slice_us_ == 0) serve(std::numeric_limits<int64_t>::max());
}

void Services::serve(int64_t deadline_us) {
  if (serving_) return;  // an answer given inside start(): the call that started it goes on
  serving_ = true;
  while (true) {
    if (batch_) {
      if (!cm_.step(batch_->second, deadline_us)) break;
      const cm_request_t r = std::move(batch_->first);
      const Reply reply = std::move(batch_->second.reply);
      batch_.reset();
      answer(r, reply);
    } else if (!queue_.empty() && !cm_.busy()) {
      const cm_request_t r = std::move(queue_.front());
      queue_.pop_front();
      start(r);
    } else {
      break;
    }
    if (monotonic_us() >= deadline_us) break;
  }
  serving_ = false;
}

void Services::answered_later() {
  if (slice_us_ == 0) serve(std::numeric_limits<int64_t>::max());
}

void Services::start(const cm_request_t& r) {
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
      answer(r, {true, fmt::format("{} controller(s) loaded", cm_.loaded())}, false, true);
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
      Batch b;
      b.names = r.names;
      b.load = r.op == cm_request_t::LOAD;
      batch_.emplace(r, std::move(b));
      return;
    }
    case cm_request_t::SWITCH: {
      for (auto [v, f] : {std::pair{&r.start, "start"}, {&r.stop, "stop"}})
        if (auto why = names_ok(*v, f); !why.empty()) return answer(r, {false, why});
      cm_request_t copy = r;
      cm_.switch_controllers(r.start, r.stop, r.strictness, [this, copy](const Reply& reply) {
        answer(copy, reply);
        answered_later();
      });
      return;
    }
    case cm_request_t::RELOAD: {
      cm_request_t copy = r;
      cm_.reload(r.force, [this, copy](const Reply& reply) {
        answer(copy, reply);
        answered_later();
      });
      return;
    }
    case cm_request_t::SET_COMPONENT_STATE: {
      if (r.names.size() != 1 || r.names.front().empty())
        return answer(r, {false, "malformed request: set-hardware-component-state needs one component name in "
                                 "names[]"});
      if (r.component_state < hardware_command_t::COMPONENT_UNCONFIGURED ||
          r.component_state > hardware_command_t::COMPONENT_FINALIZED)
        return answer(r, {false, fmt::format("malformed request: component_state {} is none of 1 unconfigured, 2 "
                                             "inactive, 3 active, 4 finalized",
                                             int(r.component_state))});
      cm_request_t copy = r;
      cm_.set_component_state(r.names.front(), static_cast<Lifecycle>(r.component_state),
                              [this, copy](const Reply& reply) {
                                answer(copy, reply);
                                answered_later();
                              });
      return;
    }
    case cm_request_t::CONFIG:
      return answer(r, cm_.publish_config());
    default:
      ++malformed_;
      answer(r, {false, fmt::format("malformed request: unknown op {}; valid ops are 1 LIST, 2 LIST_TYPES, 3 LOAD, "
                                    "4 UNLOAD, 5 SWITCH, 6 RELOAD, 8 SET_COMPONENT_STATE, 9 CONFIG",
                                    static_cast<int>(r.op))});
  }
}

}  // namespace lcm_control::cm
