// Paces the simulation and runs the hardware loop around it: real time
// (each state published on its absolute deadline on the monotonic clock, the
// step before it taken as soon as the controller has answered; newest command,
// watchdog hold)
// or lockstep (publish state k, wait for the command tagged k, step; time
// stands still while nobody answers). Serves sim_server/request between steps:
// pause (sim time holds, the state is republished so that the controller
// manager can still switch), resume, step N, reset. Publishes 1 Hz statistics.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "rt/clock.hpp"
#include "rt/log.hpp"
#include "rt/loop_stats.hpp"
#include "sim_server/sim_io.hpp"
#include "sim_server/simulation.hpp"

namespace lcm_control::sim {

// Real time, a cycle that starts a period or more late: run the steps due back to back, publishing each (the
// controller gets a burst and answers each state, StepperOptions::answer_wait_us), or take them without publishing
// and go on from the newest (the controller sees the step jump, counted as missed). Either way sim time keeps up
// with the wall clock.
enum class Overrun { CatchUp, Skip };

struct StepperOptions {
  bool lockstep = false;
  double lockstep_timeout_s = 1.0;  // lockstep: republish the state this often while waiting
  double watchdog_s = 0.1;          // real time: hold every actuator after this long without a command
  double duration_s = 0;            // sim seconds to run; 0 runs until stopped
  bool start_paused = false;        // as Gazebo's paused:=true: nothing steps until a RESUME or STEP request
  Overrun overrun = Overrun::CatchUp;  // real time
  int64_t spin_us = 0;  // real time: sleep to this long before each deadline, then poll without sleeping up to it
  // Real time: how long past a step's deadline the controller's answer to the state before it is awaited, so that a
  // catch-up burst (or a controller a little late) still gets a command per step. With Overrun::CatchUp the step is
  // taken as soon as the answer arrives and its state published when due, so neither the physics time nor the
  // controller's moves the period the controller sees; with Skip it is taken when due. 0 steps when due with the
  // newest command. Only while a controller answers (not before its first command, nor under the watchdog).
  int64_t answer_wait_us = 200;
};

class Stepper {
 public:
  Stepper(Simulation& sim, SimIo& io, const StepperOptions& options);

  // Runs until `stop` is set or the duration is reached (true), or LCM fails (false).
  bool run(const std::atomic<bool>& stop);

  // The run so far, for the line sim_server ends with: sim time over wall time since run() began, and what a
  // physics step (Simulation::step: actuators and Bullet) took on average (us), which in lockstep tells the
  // physics from the hand-over to the controller manager.
  struct Summary {
    double real_time_factor = 0, physics_us = 0;
  };
  Summary summary() const { return {real_time_factor(), run_step_exec_.mean_us()}; }

  // What a CONFIG request does: publishes the run's configuration, and says so (or why not).
  using ConfigPublisher = std::function<std::pair<bool, std::string>()>;
  void set_config_publisher(ConfigPublisher publish) { publish_config_ = std::move(publish); }

 private:
  BusLog request_log_;  // the requests served: anyone may send many, so clipped and rate-limited
  ConfigPublisher publish_config_;
  bool run_lockstep(const std::atomic<bool>& stop);
  bool run_real_time(const std::atomic<bool>& stop);
  // Paused with no steps to take: the state is republished, requests are served.
  bool holding() const { return paused_ && steps_left_ == 0; }
  bool wait_paused();
  // Publishes the state (and the clock when due or clock_again): the clock after it, kept as the last publish.
  int64_t publish(double real_time_factor, bool clock_again = false);
  void serve_requests();
  void serve(const sim_request_t& req);
  sim_response_t response_to(const sim_request_t& req, bool ok, std::string message) const;
  std::string where() const;  // "step k (t=... s)"
  void finish_step_request(const std::string& how);
  void after_step();
  void rebase(int64_t now_us);  // real time: pace from now on, without catching up what lay before
  // Real time, Overrun::Skip: the steps due by `now_us` but the last, taken without publishing; how many.
  int64_t skip_to(int64_t now_us);
  bool done() const;
  double real_time_factor() const { return real_time_factor(monotonic_us()); }
  double real_time_factor(int64_t now_us) const;
  // One physics step, its time counted: how long it took (us); *end_us, when given: the clock after it.
  int64_t step_timed(int64_t* end_us = nullptr);
  // Publishes the state of the step just taken, counting a cycle of step_us + the publish; late when the publish
  // ends after late_after_us (0: never). start_us: the clock now if just read (-1: read here). Returns the clock
  // after the publish. (The lockstep loop reads the clock a few times a step, not a dozen: each read is 40 ns.)
  int64_t publish_timed(int64_t step_us, int64_t late_after_us, int64_t start_us = -1);
  // Real time: handles messages and the statistics window until until_us (sleeping to --spin-us before it, then
  // polling), or, with answer_to >= 0, until the controller's answer to that step is here (sleeping throughout:
  // spinning for an answer would hold the CPU from a controller manager that shares it); false when LCM fails.
  // Returns early when `stop` is set.
  bool sleep_until(int64_t until_us, int64_t answer_to, const std::atomic<bool>& stop);
  void watchdog(int64_t now_us);
  void tick_statistics(int64_t now_us);

  Simulation& sim_;
  SimIo& io_;
  StepperOptions opt_;
  double period_us_;
  int64_t start_us_ = 0, start_step_ = 0;
  bool watchdog_holding_ = false;
  int64_t last_publish_us_ = -1;
  int64_t base_us_ = 0, base_step_ = 0;  // real time: step base_step_ + n is due at base_us_ + n periods
  int64_t resumed_us_ = -1;              // the watchdog counts from here after a pause
  bool paused_ = false;
  int64_t steps_left_ = 0;               // paused: steps a STEP request still takes
  sim_request_t step_request_;           // the STEP under way (request_id 0: none)
  int64_t resets_ = 0;

  // The current statistics window (1 s of wall time): where it started, and the loop's timing in it.
  struct Window {
    int64_t start_us = 0, start_step = 0, dropped_before = 0;
  } w_;
  LoopStats stats_;
  ExecStats step_exec_, publish_exec_;
  ExecStats run_step_exec_;  // the whole run: never reset
  // Per hardware component with actuators (ros2_control's per-component statistics): its actuators' share of each
  // step (Actuators::take_work_ns) and the period between its steps.
  void time_components(int64_t step_start_us);
  std::vector<int64_t> component_ns_;
  std::vector<ExecStats> component_exec_, component_period_;
  std::vector<char> component_has_actuators_;
  int64_t last_step_start_us_ = -1;
};

}  // namespace lcm_control::sim
