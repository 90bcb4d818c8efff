// Following one goal sent to an action-like controller (a trajectory or a gripper controller): its result on
// `<controller>/result` and its feedback on `<controller>/feedback`, both `Status` messages with goal_id and utime
// (trajectory_status_t, gripper_status_t); with verbose, the feedback printed by `describe`, at most 4 lines per
// second of the controller's time.
#pragma once

#include <fmt/format.h>

#include <cstdio>
#include <functional>
#include <optional>
#include <string>

#include "bus/bus.hpp"
#include "bus/messages.hpp"

namespace lcm_control::tools {

template <class Status>
class GoalWatch {
 public:
  using Describe = std::function<std::string(const Status&)>;
  GoalWatch(Bus& bus, const std::string& controller, int64_t goal_id, bool verbose, Describe describe)
      : goal_id_(goal_id), verbose_(verbose), describe_(std::move(describe)) {
    subscribe_guarded<&GoalWatch::on_result>(bus, bus.channel(controller + "/result"), this, Bus::On::Shared, 100);
    subscribe_guarded<&GoalWatch::on_feedback>(bus, bus.channel(controller + "/feedback"), this);
  }
  const std::optional<Status>& result() const { return result_; }
  size_t feedback() const { return feedback_; }

 private:
  void on_result(const lcm::ReceiveBuffer*, const std::string&, const Status* m) {
    if (m->goal_id == goal_id_ && !result_) result_ = *m;
  }
  void on_feedback(const lcm::ReceiveBuffer*, const std::string&, const Status* m) {
    if (m->goal_id != goal_id_) return;
    if (feedback_++ == 0) first_us_ = m->utime;
    if (!verbose_ || (printed_us_ >= 0 && m->utime - printed_us_ < 250000)) return;
    printed_us_ = m->utime;
    fmt::print("feedback {:.2f} s: {}\n", double(m->utime - first_us_) * 1e-6, describe_(*m));
    std::fflush(stdout);
  }

  int64_t goal_id_;
  bool verbose_;
  Describe describe_;
  std::optional<Status> result_;
  size_t feedback_ = 0;
  int64_t first_us_ = 0, printed_us_ = -1;
};

}  // namespace lcm_control::tools
