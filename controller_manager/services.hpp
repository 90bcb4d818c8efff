// The controller manager's services over LCM: cm_request_t on
// `controller_manager/request`, one cm_response_t with the same request_id on
// `controller_manager/response` (ok, a message saying what happened or why
// not, and the controllers as they are after it, at most kMaxAnswerBytes).
// Requests are served one after the other in the order they arrived; one
// that arrives while a switch or a reload is being applied waits for it.
// The controller manager program serves them between cycles, a slice at a
// time (serve()), so that no request holds up the loop.
#pragma once

#include <deque>
#include <optional>
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
// An answer's encoded size at most: its message is clipped to kMaxAnswerMessage bytes and the controllers (then the
// joints) listed are the first that fit, the message saying how many are not listed.
inline constexpr size_t kMaxAnswerBytes = 64 * 1024;
inline constexpr size_t kMaxAnswerMessage = 16 * 1024;

class Services {
 public:
  // slice_us 0: a request is served when it arrives, all at once (tests). Otherwise handle() queues it and serve()
  // does the work.
  Services(ControllerManager& cm, Bus& bus, int64_t slice_us = 0);
  void handle(const cm_request_t& request);
  // Serves the queued requests in order until they are done, one waits for a switch or reload, or monotonic_us()
  // passes deadline_us.
  void serve(int64_t deadline_us);
  bool has_work() const { return batch_.has_value() || (!queue_.empty() && !cm_.busy()); }
  int64_t malformed() const { return malformed_; }

 private:
  void answer(const cm_request_t& req, const Reply& reply, bool with_types = false, bool with_hardware = false);
  void start(const cm_request_t& r);  // answers it, hands it to the manager, or makes it the batch
  void answered_later();              // a switch or reload answered: what waited for it may go on

  ControllerManager& cm_;
  Endpoints endpoints_;
  Publisher<cm_response_t> pub_;
  int64_t slice_us_;
  std::deque<cm_request_t> queue_;
  std::optional<std::pair<cm_request_t, Batch>> batch_;  // the LOAD or UNLOAD being served
  bool serving_ = false;
  int64_t malformed_ = 0;
  BusLog log_;
};

// "load j1_controller" for the log.
std::string describe(const cm_request_t& request);

}  // namespace lcm_control::cm
