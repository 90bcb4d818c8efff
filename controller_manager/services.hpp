// The controller manager's services over LCM: cm_request_t on
// `controller_manager/request`, one cm_response_t with the same request_id on
// `controller_manager/response` (ok, a message saying what happened or why
// not, and the controllers as they are after it). Requests that arrive while
// a switch is being applied wait for it, in order.
#pragma once

#include <deque>
#include <string>

#include "bus/bus.hpp"
#include "rt/log.hpp"
#include "controller_manager/manager.hpp"
#include "bus/endpoints.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"

namespace lcm_control::cm {

// Names one request may carry in names[], start[] or stop[]: more is refused at once, before any work.
inline constexpr size_t kMaxRequestNames = 1000;

class Services {
 public:
  Services(ControllerManager& cm, Bus& bus);
  void handle(const cm_request_t& request);
  int64_t malformed() const { return malformed_; }

 private:
  void answer(const cm_request_t& req, const Reply& reply, bool with_types = false, bool with_hardware = false);
  void drain();

  ControllerManager& cm_;
  Endpoints endpoints_;
  Publisher<cm_response_t> pub_;
  std::deque<cm_request_t> deferred_;
  int64_t malformed_ = 0;
  BusLog log_;
};

// "load j1_controller" for the log.
std::string describe(const cm_request_t& request);

}  // namespace lcm_control::cm
