#include "tools/lib/clients/sim_client.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

SimClient::SimClient(Bus& bus, std::string client) : bus_(bus), client_(std::move(client)) {
  sub_ = subscribe_guarded<&SimClient::on_response>(bus_, bus_.channel(channels::kSimResponse), this);
}

SimClient::~SimClient() { bus_.unsubscribe(sub_); }

void SimClient::on_response(const lcm::ReceiveBuffer*, const std::string&, const sim_response_t* m) {
  const auto it = answers_.find(m->request_id);
  if (it != answers_.end()) it->second = *m;
}

std::string sim_request_name(const sim_request_t& req) {
  switch (req.op) {
    case sim_request_t::STATUS: return "status";
    case sim_request_t::PAUSE: return "pause";
    case sim_request_t::RESUME: return "resume";
    case sim_request_t::STEP: return fmt::format("step {}", req.steps);
    case sim_request_t::RESET: return "reset";
    case sim_request_t::FAIL_COMPONENT: return fmt::format("fail-hardware-component {}", req.component);
    case sim_request_t::APPLY_WRENCH: return fmt::format("apply-body-wrench {}", req.link);
  }
  return fmt::format("op {}", int(req.op));
}

sim_response_t SimClient::call(sim_request_t req, double timeout_s) {
  req.utime = wall_us();
  req.request_id = new_request_id();
  req.client = client_;
  req.num_joints = int32_t(std::min(req.joint.size(), req.position.size()));
  answers_[req.request_id].request_id = 0;  // placeholder until the answer comes
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  auto answered = [&] { return answers_[req.request_id].request_id == req.request_id; };
  while (!answered() && !stop_requested()) {
    const double left = double(end - monotonic_us()) / 1e6;
    if (left <= 0) break;
    bus_.publish(channels::kSimRequest, req);
    pump_until(bus_, answered, std::min(1.0, left));
  }
  const sim_response_t got = answers_[req.request_id];
  answers_.erase(req.request_id);
  if (got.request_id == req.request_id) return got;
  if (stop_requested()) throw std::runtime_error(fmt::format("interrupted while waiting for {}", sim_request_name(req)));
  throw BusError(fmt::format(
      "no answer from sim_server within {} to {} (sent on '{}', nothing came back on '{}'): is sim_server running on "
      "{}{}? (same --lcm-url/LCM_DEFAULT_URL and --namespace)",
      seconds_text(timeout_s), sim_request_name(req), bus_.channel(channels::kSimRequest),
      bus_.channel(channels::kSimResponse), bus_.url(),
      bus_.ns().empty() ? " without a namespace" : " with namespace '" + bus_.ns() + "'"));
}

namespace {
sim_request_t request(int8_t op) {
  sim_request_t r{};
  r.op = op;
  return r;
}
}  // namespace

sim_response_t SimClient::status(double t) { return call(request(sim_request_t::STATUS), t); }
sim_response_t SimClient::pause(double t) { return call(request(sim_request_t::PAUSE), t); }
sim_response_t SimClient::resume(double t) { return call(request(sim_request_t::RESUME), t); }

sim_response_t SimClient::step(int64_t steps, double t) {
  const sim_response_t s = status(t);
  sim_request_t r = request(sim_request_t::STEP);
  r.steps = steps;
  // Real time takes the steps' sim time; lockstep usually less. Twice that, on top of the usual wait.
  return call(r, t + 2.0 * double(steps) * double(std::max(0, s.period_us)) * 1e-6);
}

sim_response_t SimClient::fail_component(const std::string& component, const std::string& reason, double t) {
  sim_request_t r = request(sim_request_t::FAIL_COMPONENT);
  r.component = component;
  r.reason = reason;
  return call(r, t);
}

sim_response_t SimClient::apply_wrench(const std::string& link, const std::array<double, 3>& force,
                                       const std::array<double, 3>& torque, double duration_s, double t) {
  sim_request_t r = request(sim_request_t::APPLY_WRENCH);
  r.link = link;
  r.force.x = force[0], r.force.y = force[1], r.force.z = force[2];
  r.torque.x = torque[0], r.torque.y = torque[1], r.torque.z = torque[2];
  r.duration = duration_s;
  return call(r, t);
}

sim_response_t SimClient::reset(const InitialPositions& start, double t) {
  sim_request_t r = request(sim_request_t::RESET);
  for (const auto& [joint, q] : start) {
    r.joint.push_back(joint);
    r.position.push_back(q);
  }
  return call(r, t);
}

}  // namespace lcm_control::tools
