#include "tools/lib/clients/cm_client.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "bus/messages.hpp"
#include "description/hardware_components.hpp"
#include "tools/lib/clients/census.hpp"
#include "tools/lib/clients/command_check.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

CmClient::CmClient(Bus& bus, std::string client) : bus_(bus), client_(std::move(client)) {
  sub_ = subscribe_guarded<&CmClient::on_response>(bus_, response_channel(), this, Bus::On::Shared, 100);
}

CmClient::~CmClient() { bus_.unsubscribe(sub_); }

std::string CmClient::request_channel() const { return bus_.channel(channels::kCmRequest); }
std::string CmClient::response_channel() const { return bus_.channel(channels::kCmResponse); }

void CmClient::on_response(const lcm::ReceiveBuffer*, const std::string&, const cm_response_t* m) {
  const auto first = registered_.find(m->request_id);
  if (first != registered_.end() && first->second == m->utime) return;  // the registration's answer, repeated
  const auto it = answers_.find(m->request_id);
  if (it != answers_.end()) it->second = *m;
}

std::string CmClient::no_answer(const std::string& what, double timeout_s) const {
  return fmt::format(
      "no answer from the controller manager within {} to {} (sent on '{}', nothing came back on '{}'): is "
      "controller_manager running on {}{}? (same --lcm-url/LCM_DEFAULT_URL and --namespace)",
      seconds_text(timeout_s), what, request_channel(), response_channel(), bus_.url(),
      bus_.ns().empty() ? " without a namespace" : " with namespace '" + bus_.ns() + "'");
}

namespace {
std::string what_of(const cm_request_t& r) {
  switch (r.op) {
    case cm_request_t::LIST: return "list";
    case cm_request_t::LIST_TYPES: return "list-types";
    case cm_request_t::LOAD: return fmt::format("load {}", fmt::join(r.names, " "));
    case cm_request_t::UNLOAD: return fmt::format("unload {}", fmt::join(r.names, " "));
    case cm_request_t::SWITCH:
      return fmt::format("switch (start [{}], stop [{}])", fmt::join(r.start, " "), fmt::join(r.stop, " "));
    case cm_request_t::RELOAD: return "reload";
    case cm_request_t::SET_COMPONENT_STATE:
      return fmt::format("set-hardware-component-state {} {}", fmt::join(r.names, " "),
                         lifecycle_label(r.component_state));
    default: return "a request";
  }
}
}  // namespace

int64_t CmClient::send(cm_request_t& req, std::set<int64_t>& ids) {
  req.utime = wall_us();
  req.request_id = new_request_id();
  req.client = client_;
  req.num_names = int32_t(req.names.size());
  req.num_start = int32_t(req.start.size());
  req.num_stop = int32_t(req.stop.size());
  if (req.strictness == 0) req.strictness = cm_request_t::STRICT;
  ids.insert(req.request_id);
  answers_[req.request_id].request_id = 0;  // placeholder until the answer comes
  bus_.publish(channels::kCmRequest, req);
  return req.request_id;
}

cm_response_t CmClient::command_source(command_source_t req, double timeout_s) {
  req.utime = wall_us();
  req.request_id = new_request_id();
  req.client = client_;
  req.num_expressions = int32_t(req.expressions.size());
  answers_[req.request_id].request_id = 0;
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  std::optional<cm_response_t> got;
  for (double left = timeout_s; !got && left > 0 && !stop_requested();
       left = double(end - monotonic_us()) / 1e6) {
    bus_.publish(channels::kCmCommandSource, req);  // again under the same id: the manager registers it once
    got = wait_answer({req.request_id}, std::min(kResendS, left));
  }
  if (!got) {
    throw CmTimeout(fmt::format(
        "no answer from the controller manager within {} to the command source for '{}' (sent on '{}', nothing came "
        "back on '{}'): is controller_manager running on {}{}? (same --lcm-url/LCM_DEFAULT_URL and --namespace)",
        seconds_text(timeout_s), req.controller, bus_.channel(channels::kCmCommandSource), response_channel(),
        bus_.url(), bus_.ns().empty() ? " without a namespace" : " with namespace '" + bus_.ns() + "'"));
  }
  answers_[req.request_id].request_id = 0;  // the next answer with this id says it ended
  registered_[req.request_id] = got->utime;
  return *got;
}

std::optional<cm_response_t> CmClient::source_ended(int64_t request_id, double timeout_s) {
  auto got = wait_answer({request_id}, timeout_s);
  if (got) {
    answers_.erase(request_id);
    registered_.erase(request_id);
  }
  return got;
}

std::optional<cm_response_t> CmClient::wait_answer(const std::set<int64_t>& ids, double timeout_s) {
  std::optional<cm_response_t> got;
  pump_until(
      bus_,
      [&] {
        for (int64_t id : ids) {
          const auto it = answers_.find(id);
          if (it != answers_.end() && it->second.request_id == id) {
            got = it->second;
            return true;
          }
        }
        return false;
      },
      timeout_s);
  return got;
}

namespace {
bool shows_done(const cm_request_t& r, const cm_response_t& list) {
  auto state_of = [&](const std::string& name) -> std::string {
    for (const auto& c : list.controllers)
      if (c.name == name) return c.state;
    return "";
  };
  switch (r.op) {
    case cm_request_t::LOAD:
      return std::all_of(r.names.begin(), r.names.end(), [&](const auto& n) { return !state_of(n).empty(); });
    case cm_request_t::UNLOAD:
      return std::all_of(r.names.begin(), r.names.end(), [&](const auto& n) { return state_of(n).empty(); });
    case cm_request_t::SWITCH:
      return std::all_of(r.start.begin(), r.start.end(), [&](const auto& n) { return state_of(n) == "running"; }) &&
             std::all_of(r.stop.begin(), r.stop.end(), [&](const auto& n) { return state_of(n) != "running"; });
    default: return false;
  }
}
}  // namespace

cm_response_t CmClient::call(cm_request_t req, double timeout_s) {
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  auto left = [&] { return double(end - monotonic_us()) / 1e6; };
  const bool checkable =
      req.op == cm_request_t::LOAD || req.op == cm_request_t::UNLOAD || req.op == cm_request_t::SWITCH;
  std::set<int64_t> ids, list_ids;
  cm_request_t list_req = cm_request(cm_request_t::LIST);
  std::optional<cm_response_t> answer;
  // A manager heard in another namespace (and none in ours) is named at once instead of after the whole timeout.
  NamespaceProbe probe(bus_, {channels::kCmStatistics, channels::kJointStates, channels::kHardwareState});
  const int64_t start = monotonic_us();
  auto hint = [&] { return monotonic_us() - start >= kHintAfterUs ? probe.hint() : std::string(); };
  while (!stop_requested() && left() > 0) {
    send(req, ids);
    const int64_t slice_end = monotonic_us() + int64_t(std::min(1.0, left()) * 1e6);
    while (!answer && monotonic_us() < slice_end && hint().empty())
      answer = wait_answer(ids, std::min(0.1, double(slice_end - monotonic_us()) / 1e6));
    if (answer) break;
    if (const std::string h = hint(); !h.empty()) {
      for (int64_t id : ids) answers_.erase(id);
      for (int64_t id : list_ids) answers_.erase(id);
      const double waited = std::round(double(monotonic_us() - start) / 1e5) / 10;  // "0.3 s"
      throw CmTimeout(fmt::format("{}; {}", no_answer(what_of(req), waited), h), h);
    }
    if (!checkable || left() <= 0) continue;
    send(list_req, list_ids);
    const auto listed = wait_answer(list_ids, std::min(1.0, left()));
    if ((answer = wait_answer(ids, 0))) break;
    if (listed && shows_done(req, *listed)) {
      answer = *listed;
      answer->op = req.op;
      answer->request_id = req.request_id;
      answer->ok = true;
      answer->message = "done (its answer was lost on the bus; the controller list shows it)";
      break;
    }
  }
  for (int64_t id : ids) answers_.erase(id);
  for (int64_t id : list_ids) answers_.erase(id);
  if (answer) return *answer;
  if (stop_requested()) throw std::runtime_error(fmt::format("interrupted while waiting for {}", what_of(req)));
  throw CmTimeout(no_answer(what_of(req), timeout_s));
}

cm_response_t CmClient::list(double t) { return call(cm_request(cm_request_t::LIST), t); }
cm_response_t CmClient::list_types(double t) { return call(cm_request(cm_request_t::LIST_TYPES), t); }
cm_response_t CmClient::load(const std::vector<std::string>& names, double t) {
  return call(cm_request(cm_request_t::LOAD, names), t);
}
cm_response_t CmClient::unload(const std::vector<std::string>& names, double t) {
  return call(cm_request(cm_request_t::UNLOAD, names), t);
}
cm_response_t CmClient::switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop,
                                           bool strict, double t) {
  return call(cm_request(cm_request_t::SWITCH, {}, start, stop, strict ? cm_request_t::STRICT : cm_request_t::BEST_EFFORT),
              t);
}
cm_response_t CmClient::set_component_state(const std::string& component, int8_t state, double t) {
  cm_request_t r = cm_request(cm_request_t::SET_COMPONENT_STATE, {component});
  r.component_state = state;
  return call(r, t);
}
cm_response_t CmClient::reload(bool force, double t) {
  cm_request_t r = cm_request(cm_request_t::RELOAD);
  r.force = force;
  return call(r, t);
}

cm_response_t CmClient::wait_for_manager(double timeout_s, const std::function<void()>& on_wait) {
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  bool said = false;
  for (;;) {
    const double left = double(end - monotonic_us()) / 1e6;
    if (left <= 0 || stop_requested()) break;
    try {
      return list(std::min(0.5, left));
    } catch (const CmTimeout&) {
      if (!said && on_wait) on_wait();
      said = true;
    }
  }
  if (stop_requested()) throw std::runtime_error("interrupted while waiting for the controller manager");
  throw CmTimeout(no_answer("list", timeout_s));
}

std::string without_controller_prefix(const std::string& message, const std::string& controller) {
  const std::string prefix = controller + ": ";
  return message.rfind(prefix, 0) == 0 ? message.substr(prefix.size()) : message;
}

std::string no_goal_result(CmClient& cm, const Bus& bus, const std::string& controller, double timeout_s,
                           size_t feedback, const std::string& longer) {
  const std::string head = fmt::format("no result from '{}' on '{}' within {}", controller,
                                       bus.channel(controller + "/result"), seconds_text(timeout_s));
  try {
    const cm_response_t listed = cm.list(1.0);
    for (const auto& c : listed.controllers) {
      if (c.name != controller) continue;
      if (c.state != "running")
        return fmt::format("{}: the controller manager now lists it as {}, not running (cmctl list)", head, c.state);
      if (feedback > 0)
        return fmt::format("{}: it is running and sent {} feedback messages for this goal{}{}", head, feedback,
                           longer.rfind("(", 0) == 0 ? " " : "; ", longer);
      if (const auto cause = hardware_cause(listed))
        return fmt::format("{}: it is running but sent no feedback for this goal on '{}': {}", head,
                           bus.channel(controller + "/feedback"), *cause);
      return fmt::format("{}: it is running but sent no feedback for this goal on '{}': does its time advance? (is "
                         "sim_server running and stepping?)",
                         head, bus.channel(controller + "/feedback"));
    }
    return fmt::format("{}: the controller manager no longer lists it (cmctl list)", head);
  } catch (const CmTimeout&) {
    return fmt::format("{}, and the controller manager no longer answers on '{}': is it running? (cmctl list)", head,
                       cm.request_channel());
  }
}

std::string ros2_state(const std::string& state) { return state == "running" ? "active" : "inactive"; }

std::string hardware_interfaces_text(const std::vector<joint_interfaces_t>& joints) {
  std::string out = "command interfaces\n";
  for (const auto& j : joints)
    for (const auto& c : j.command)
      out += fmt::format("\t{}/{} [available] [{}]\n", j.joint, c,
                         c == j.claimed ? "claimed by " + j.claimed_by : "unclaimed");
  out += "state interfaces\n";
  for (const auto& j : joints)
    for (const auto& s : j.state) out += fmt::format("\t{}/{}\n", j.joint, s);
  return out;
}

std::string hardware_components_text(const std::vector<hardware_component_t>& components, bool verbose) {
  if (components.empty()) return "no hardware components (the robot has no transmissions and no <ros2_control>)\n";
  std::string out;
  for (const auto& c : components) {
    out += fmt::format("{}: {}\n", c.name, c.state_label);
    out += fmt::format("\ttype: {}  plugin: {}  runs as: {}\n", c.type, c.plugin.empty() ? "-" : c.plugin, c.kind);
    if (!c.error.empty()) out += fmt::format("\tlast error: {}\n", c.error);
    out += fmt::format("\tjoints: {}\n", c.joints.empty() ? "-" : fmt::format("{}", fmt::join(c.joints, ", ")));
    if (verbose || !c.interfaces.empty())
      out += fmt::format("\tother state interfaces: {}\n",
                         c.interfaces.empty() ? "-" : fmt::format("{}", fmt::join(c.interfaces, ", ")));
    out += fmt::format("\tused by: {}\n",
                       c.controllers.empty() ? "-" : fmt::format("{}", fmt::join(c.controllers, ", ")));
  }
  return out;
}

namespace {
// A controller's joints in the list's column: all of them up to three, else the first and last with the count (the
// whole list is `cmctl list --verbose`'s).
std::string joints_cell(const std::vector<std::string>& joints, bool verbose) {
  if (joints.empty()) return "-";
  if (verbose || joints.size() <= 3) return fmt::format("{}", fmt::join(joints, ","));
  return fmt::format("{}..{} ({})", joints.front(), joints.back(), joints.size());
}
}  // namespace

std::string controller_table(const std::vector<controller_info_t>& controllers, bool ros2, bool verbose) {
  const bool chaining = std::any_of(controllers.begin(), controllers.end(), [](const auto& c) { return c.chainable; });
  std::vector<std::vector<std::string>> rows = {{"NAME", "TYPE", "STATE", "JOINTS", "INTERFACE"}};
  if (chaining) rows[0].push_back("CHAINED MODE");
  if (chaining && verbose) rows[0].push_back("REFERENCE INTERFACES");
  for (const auto& c : controllers) {
    rows.push_back({c.name, c.type, ros2 ? ros2_state(c.state) : c.state, joints_cell(c.joints, verbose),
                    c.hardware_interface.empty() ? "-" : c.hardware_interface});
    if (chaining) rows.back().push_back(!c.chainable ? "-" : c.chained_mode ? "yes" : "no");
    if (chaining && verbose)
      rows.back().push_back(c.references.empty() ? "-" : fmt::format("{}", fmt::join(c.references, ",")));
  }
  return table_text(rows);
}

std::string table_text(const std::vector<std::vector<std::string>>& rows, size_t right_from) {
  std::vector<size_t> width;
  for (const auto& r : rows)
    for (size_t k = 0; k < r.size(); ++k) {
      if (width.size() <= k) width.push_back(0);
      width[k] = std::max(width[k], r[k].size());
    }
  std::string out;
  for (const auto& r : rows) {
    for (size_t k = 0; k < r.size(); ++k) {
      if (k > 0) out += "  ";
      out += k >= right_from ? fmt::format("{:>{}}", r[k], width[k])
             : k + 1 < r.size() ? fmt::format("{:<{}}", r[k], width[k])
                                : r[k];
    }
    out += "\n";
  }
  return out;
}

}  // namespace lcm_control::tools
