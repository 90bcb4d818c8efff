#include "tools/cm_client.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include "tools/support.hpp"

namespace lcm_control::tools {

CmClient::CmClient(Bus& bus, std::string client) : bus_(bus), client_(std::move(client)) {
  sub_ = bus_.lcm().subscribe(response_channel(), &CmClient::on_response, this);
  sub_->setQueueCapacity(100);
}

std::string CmClient::request_channel() const { return bus_.channel(channels::kCmRequest); }
std::string CmClient::response_channel() const { return bus_.channel(channels::kCmResponse); }

void CmClient::on_response(const lcm::ReceiveBuffer*, const std::string&, const cm_response_t* m) {
  if (waiting_for_ != 0 && m->request_id == waiting_for_) {
    answer_ = *m;
    answered_ = true;
  }
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
    default: return "a request";
  }
}
}  // namespace

cm_response_t CmClient::call(cm_request_t req, double timeout_s) {
  req.utime = wall_us();
  req.request_id = new_request_id();
  req.client = client_;
  req.num_names = int32_t(req.names.size());
  req.num_start = int32_t(req.start.size());
  req.num_stop = int32_t(req.stop.size());
  if (req.strictness == 0) req.strictness = cm_request_t::STRICT;
  waiting_for_ = req.request_id;
  answered_ = false;
  bus_.publish(channels::kCmRequest, req);
  const bool ok = pump_until(bus_, [&] { return answered_; }, timeout_s);
  waiting_for_ = 0;
  if (!ok) {
    if (stop_requested()) throw std::runtime_error(fmt::format("interrupted while waiting for {}", what_of(req)));
    throw CmTimeout(no_answer(what_of(req), timeout_s));
  }
  return answer_;
}

cm_response_t CmClient::list(double t) {
  cm_request_t r{};
  r.op = cm_request_t::LIST;
  return call(r, t);
}
cm_response_t CmClient::list_types(double t) {
  cm_request_t r{};
  r.op = cm_request_t::LIST_TYPES;
  return call(r, t);
}
cm_response_t CmClient::load(const std::vector<std::string>& names, double t) {
  cm_request_t r{};
  r.op = cm_request_t::LOAD;
  r.names = names;
  return call(r, t);
}
cm_response_t CmClient::unload(const std::vector<std::string>& names, double t) {
  cm_request_t r{};
  r.op = cm_request_t::UNLOAD;
  r.names = names;
  return call(r, t);
}
cm_response_t CmClient::switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop,
                                           bool strict, double t) {
  cm_request_t r{};
  r.op = cm_request_t::SWITCH;
  r.start = start;
  r.stop = stop;
  r.strictness = strict ? cm_request_t::STRICT : cm_request_t::BEST_EFFORT;
  return call(r, t);
}
cm_response_t CmClient::reload(bool force, double t) {
  cm_request_t r{};
  r.op = cm_request_t::RELOAD;
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

std::string controller_table(const std::vector<controller_info_t>& controllers) {
  std::vector<std::vector<std::string>> rows = {{"NAME", "TYPE", "STATE", "JOINTS", "INTERFACE"}};
  for (const auto& c : controllers)
    rows.push_back({c.name, c.type, c.state, c.joints.empty() ? "-" : fmt::format("{}", fmt::join(c.joints, ",")),
                    c.hardware_interface.empty() ? "-" : c.hardware_interface});
  std::vector<size_t> width(5, 0);
  for (const auto& r : rows)
    for (size_t k = 0; k < r.size(); ++k) width[k] = std::max(width[k], r[k].size());
  std::string out;
  for (const auto& r : rows) {
    std::string line;
    for (size_t k = 0; k < r.size(); ++k)
      line += k + 1 < r.size() ? fmt::format("{:<{}}  ", r[k], width[k]) : r[k];
    out += line + "\n";
  }
  return out;
}

}  // namespace lcm_control::tools
