// sim_server's side of the LCM hardware loop (docs/hardware-protocol.md):
// publishes hardware/state (every control step, on the bus's hardware loop), and clock and a floating
// base's ground truth (sim_server/base_pose) at the clock's rate, from
// preallocated buffers; takes
// hardware/command (checked, and dropped and counted when malformed, NaN,
// wrong-size or from another session; an actuator commanded in a mode its
// joint does not offer holds, counted and said once), e_stop,
// sim_server/gains/set and sim_server/request (queued for the stepper, a
// repeated request_id answered again, not queued twice); publishes the gains in
// force, the answers and the statistics.
// Handlers run inside poll_until(), i.e. between control steps.
#pragma once

#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "bus/answer_ledger.hpp"
#include "bus/bus.hpp"
#include "bus/endpoints.hpp"
#include "bus/gains_service.hpp"
#include "rt/log.hpp"
#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "lcm_control/sim_response_t.hpp"
#include "sim_server/simulation.hpp"

namespace lcm_control::sim {

class SimIo {
 public:
  // clock_every: control steps per `clock` message (clock_every_for()).
  SimIo(Bus& bus, Simulation& sim, bool lockstep, int clock_every = 1);
  SimIo(const SimIo&) = delete;
  SimIo& operator=(const SimIo&) = delete;

  int64_t session() const { return session_; }

  // hardware/state for the simulation's current step, and `clock` once on every
  // clock_every-th step (and the first), or again with `clock_again` (paused: a tool that starts then learns the
  // sim time).
  void publish_state(double real_time_factor, bool clock_again = false);
  void publish_statistics(const loop_stats_t& stats);

  // Handles LCM messages as they come until `deadline_us` (monotonic_us()), or until a command is
  // accepted if `until_command` (one answering `answering_step` or later), or a request is queued if `until_request`;
  // at least one non-blocking pass. False if LCM failed.
  bool poll_until(int64_t deadline_us, bool until_command = false, bool until_request = false,
                  int64_t answering_step = -1);

  // sim_server/request, oldest first. answer() publishes on sim_server/response and remembers the answer, so that a
  // client resending the request (a lost answer) gets it again.
  bool has_request() const { return !requests_.empty(); }
  sim_request_t take_request();
  void answer(const sim_response_t& answer);
  // After Simulation::reset(): the pending command is forgotten, `clock` starts again, and commands answering the
  // states before the reset (up to `previous_step`, still in flight) are stale rather than dropped as forged.
  void after_reset(int64_t previous_step);

  // Lockstep: only a command tagged with this step is accepted (others are ignored, counted stale).
  void expect_step(int64_t step) { expected_step_ = step; }
  // Real time: a command answering a state more than `steps` old is stale (a controller manager that was stopped
  // and resumes must not replay its backlog onto the robot); 0: no limit.
  void set_max_command_age(int64_t steps) { max_age_ = steps; }
  bool has_command() const { return has_pending_; }
  // Real time: a command answering state `step` (or a later one) has been accepted (poll_until waits for one).
  bool answered(int64_t step) const { return last_step_ >= step; }
  // Hands the newest accepted command to the actuators; false if none arrived since the last call.
  bool take_command();
  // monotonic_us() when the newest command was accepted, -1 before the first.
  int64_t last_command_us() const { return last_command_us_; }

  // Malformed, NaN, wrong size or session, and what the hardware loop skipped before decoding (Bus::hardware_skipped).
  int64_t dropped() const { return dropped_ + bus_.hardware_skipped(); }
  Bus& bus() { return bus_; }
  int64_t rejected_modes() const { return rejected_modes_; }  // actuator commands in a mode not offered (held)
  int64_t stale() const { return stale_; }      // well-formed but for another step
  int64_t foreign_states() const { return foreign_states_; }  // hardware/state of another simulator on our channel

 private:
  void on_command(const lcm::ReceiveBuffer& rb);
  void on_e_stop(const lcm::ReceiveBuffer& rb);
  void on_state(const lcm::ReceiveBuffer& rb);
  void on_request(const lcm::ReceiveBuffer& rb);
  std::string why_rejected();
  void drop(const std::string& why);
  void reject_mode(int i, int8_t mode);
  PidLookup pid_lookup();
  void publish_base_pose();

  Bus& bus_;
  Simulation& sim_;
  const bool lockstep_;
  const int clock_every_;
  int64_t clock_step_ = -1;  // step of the last `clock` sent
  const int64_t session_;
  const std::string state_channel_;
  Endpoints endpoints_, hw_endpoints_;  // the shared bus, the hardware loop
  Publisher<hardware_state_t> state_pub_;
  Publisher<sim_clock_t> clock_pub_;
  Publisher<odometry_t> base_pub_;
  Publisher<loop_stats_t> stats_pub_;
  Publisher<sim_response_t> response_pub_;

  hardware_state_t state_{};
  sim_clock_t clock_;
  odometry_t base_;
  bool floating_base_ = false;

  hardware_command_t cmd_;  // decoded in place: its arrays keep their capacity
  bool components_listed_ = false;  // the last command listed the components (one was not active)
  std::vector<std::string> bound_names_;  // the actuator list of the commands being taken, as matched
  std::vector<int> slot_;                 // our actuator i is the command's slot_[i]
  std::vector<int8_t> pending_mode_;
  std::vector<int8_t> rejected_warned_;  // per actuator: the refused mode last said
  int64_t rejected_modes_ = 0;
  std::vector<double> pending_value_;
  std::vector<double> pending_damping_;
  bool has_pending_ = false;
  int64_t expected_step_ = -1, last_step_ = -1, last_command_us_ = -1;
  int64_t foreign_states_ = 0;
  int64_t dropped_ = 0, stale_ = 0, dropped_logged_ = 0, last_drop_log_us_ = 0, max_age_ = 0;
  int64_t pre_reset_step_ = -1;  // commands up to this step answer states from before the last reset
  e_stop_t e_stop_msg_;
  std::deque<sim_request_t> requests_;
  AnswerLedger<sim_response_t> ledger_;  // a repeated request_id is answered again, not done twice
  BusLog log_;  // e-stop and gains lines: anyone can send those
};

}  // namespace lcm_control::sim
