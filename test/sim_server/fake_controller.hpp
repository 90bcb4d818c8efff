// A stand-in controller_manager for end-to-end tests: it answers every
// hardware/state of a real sim_server with a hardware_command_t built by a
// policy, and keeps every state it saw (the first copy of each step).
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lcm_control::sim::testing {

class FakeController {
 public:
  // Fills command[] (actuator units) for a state; mode[] and the header are preset from the state.
  using Policy = std::function<void(const hardware_state_t&, hardware_command_t&)>;

  FakeController(lcm::LCM& lc, const std::string& ns = "");
  ~FakeController();

  Policy policy;
  bool answering = true;  // false: keep listening, stop answering
  // Called before the command of a new step goes out (to publish e-stops, gains, bad commands...).
  std::function<void(const hardware_state_t&)> before_answer;

  std::vector<hardware_state_t> states;
  int republished = 0;  // states received again for a step already seen
  // Answers this process sent more than kLateAnswerUs after their state arrived (a stall of the test, not of the
  // server: sim_server counts each as a missed step when it waits less than that for its answer).
  static constexpr int64_t kLateAnswerUs = 200;
  int64_t late_answers = 0;

  // Pumps LCM until a state with step >= `step` arrived; false on timeout.
  bool run_until_step(int64_t step, double timeout_s);
  // Pumps LCM for `seconds` of wall time.
  void pump_for(double seconds);

  void publish_command(const hardware_command_t& cmd);
  const std::string& command_channel() const { return command_channel_; }
  lcm::LCM& lcm() { return lc_; }

 private:
  void on_state(const lcm::ReceiveBuffer*, const std::string&, const hardware_state_t* s);

  lcm::LCM& lc_;
  std::string command_channel_;
  lcm::Subscription* sub_;
  hardware_command_t last_;
  bool have_last_ = false;
};

// A sim_server process on a URL of its own, with an LCM instance for the test side.
struct SimServerProcess {
  std::string url = lcm_control::testing::unique_lcm_url();
  lcm::LCM lc{url};
  std::unique_ptr<lcm_control::testing::ChildProcess> process;

  // Starts sim_server with the robot and extra flags; false (with the output in `why`) if it is not ready in 10 s.
  bool start(const std::vector<std::string>& flags, const std::string& urdf, const std::string& config,
             std::string* why = nullptr);
  std::string output() const { return process ? process->output() : ""; }
};

}  // namespace lcm_control::sim::testing
