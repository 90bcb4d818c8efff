// The real-time loop: one cycle per hardware state: read (actuator -> joint),
// update every running controller in load order with the period measured on
// the hardware clock, apply a pending switch (stopping() then starting(), all
// in this cycle), the URDF's soft limits on the commands, write (joint ->
// actuator) tagged with the step it answers.
// A new session, time or step going backwards (a reset), an e-stop release or
// a resume after silence restarts the running controllers from the current
// state. The same step again (a lockstep republish, a paused hardware) updates
// nothing, but a pending switch is applied on it, the controllers it started
// are updated on it, and the command rewritten.
// Command sources deliver their due ticks after restarts, before the updates.
// A hardware component the state reports in error (hardware_state_t::error_component) that is inactive or active is
// set unconfigured before the updates, and every running controller using it is stopped (stopped_by_error) in that
// cycle; a pending component state change (set_pending_component) applies with the pending switch, after its stops.
// A pending start of a controller whose components no longer allow it is not made (start_refused).
// A controller that fails in its update (Controller::fail) is stopped there, and its fallback controllers started.
// Controllers update in reorder()'s order: one that writes another's reference interfaces (ROS 2 chaining) first;
// a chainable controller is in chained mode while a running controller owns one of its reference interfaces.
// An is_async controller (ControllerSlot::async) is handed its due update when its thread is idle, and its commands
// are taken back in the first cycle after (not while messages for it are held: those are delivered between cycles
// first); in lockstep it runs in the cycle, as the others do. Its starting(),
// stopping() and restart() run in the loop when its thread is idle, else before its next update.
// A started controller's joints hold their measured position (velocity and
// effort 0) until its first update, unless taken over from a controller
// stopped in the same switch, whose last command they keep.
// cycle() does not allocate, log or lock.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "controller_manager/async_update.hpp"
#include "controller_interface/controller.hpp"
#include "controller_manager/hardware.hpp"
#include "rt/loop_stats.hpp"
#include "rt/outbox.hpp"

namespace lcm_control::cm {

// What the loop runs in each cycle after restarts and before the updates, owned by whoever sets it (the command
// sources deliver their due ticks there). Must not allocate, log or block.
class BeforeUpdate {
 public:
  virtual ~BeforeUpdate() = default;
  virtual void before_update(const Time& now) = 0;
};

struct ControllerSlot {
  std::string name, type;
  // An is_async controller's (ROS 2): the hardware copy it was initialised on and the outbox its thread publishes
  // through; declared before the controller, which refers to them.
  std::unique_ptr<Hardware> shadow;
  std::unique_ptr<Outbox> outbox;
  std::unique_ptr<Controller> controller;
  std::unique_ptr<Endpoints> endpoints;  // declared after the controller: unsubscribes first
  std::vector<JointData*> claimed;  // joints it commands
  std::vector<GpioData*> claimed_gpios;  // <gpio> command interfaces it commands
  bool running = false;
  bool ever_started = false;
  // Its own update_rate (ROS 2): updated on one cycle in round(the hardware's rate / update_rate), counted from its
  // first cycle; 0: every cycle.
  double update_rate_hz = 0;
  int64_t first_step = -1;         // the step of its first update since it started (-1: none yet)
  int64_t last_update_utime = -1;  // hardware time of its last update (-1: none since it started)
  bool stopped_by_error = false;  // stopped by the loop because a component it uses failed (the manager clears it)
  // Stopped because a controller whose reference interfaces it writes (directly or down its chain) was stopped by a
  // failure or its component leaving active: a chain runs whole (ros2_control). The manager reports it and clears it.
  const ControllerSlot* chain_stopped_by = nullptr;
  bool start_refused = false;     // a pending start not made: a component it uses left the state it needs
  // ROS 2's fallback_controllers: started in the cycle it fails (Controller::fail), those loaded, stopped, allowed by
  // their components and whose claims are free then; fallback_started says which (for the manager's report).
  std::vector<std::string> fallbacks;
  std::vector<char> fallback_started;
  const char* failure = nullptr;   // why it failed in the last cycle; the manager reports it and clears this
  int64_t failure_step = -1;
  ExecStats exec;                  // its updates' execution times
  ExecStats period;                // the wall-clock time between its updates
  int64_t last_update_mono = -1;   // monotonic µs of its last update (-1: none since it started)
  // An is_async controller's thread; declared last, so stopped first.
  std::unique_ptr<AsyncUpdate> async;
  const char* state() const { return running ? "running" : ever_started ? "stopped" : "initialized"; }
};

// Whether the components `c` uses let it run (those it commands active, those it reads inactive or active), and
// whether `component` going to `state` stops it.
bool may_run(const Controller& c, const std::vector<ComponentData>& components);
bool affected_by(const Controller& c, int component, Lifecycle state);

class Loop {
 public:
  explicit Loop(Hardware& hw) : hw_(hw) {}

  // Load order. Add and remove only between cycles, then reorder().
  std::vector<std::unique_ptr<ControllerSlot>>& slots() { return slots_; }
  const std::vector<std::unique_ptr<ControllerSlot>>& slots() const { return slots_; }
  // The update order: load order, but a controller that writes another's reference interfaces (chaining) before
  // it, so that the follower uses this cycle's references. Allocates: between cycles only.
  void reorder();
  const std::vector<ControllerSlot*>& order() const { return order_; }

  enum class Outcome { Answered, Repeated };
  // One control step. Repeated: the same step again (a lockstep republish or a
  // paused hardware) with no switch pending: controllers are not updated and
  // `command` still holds the last answer.
  Outcome cycle(const hardware_state_t& state, hardware_command_t& command);

  // A switch to apply right after the next update (or now with apply_now()).
  void set_pending_switch(const std::vector<ControllerSlot*>& stop, const std::vector<ControllerSlot*>& start);
  // With the pending switch: component `index` (Hardware::components()) goes to `state` after the stops.
  void set_pending_component(int index, Lifecycle state);
  bool switch_pending() const { return pending_; }
  void apply_now();
  void cancel_pending();
  // Step and utime at which the last switch was applied (-1 if not in a cycle).
  int64_t last_switch_step() const { return last_switch_step_; }

  // After silence: the next cycle restarts the running controllers.
  void restart_next_cycle() { restart_ = true; }
  void stop_all();  // stopping() on every running controller, claims released
  void set_before_update(BeforeUpdate* hook) { before_update_ = hook; }

  const Time& now() const { return now_; }
  int64_t step() const { return step_; }
  bool has_state() const { return have_state_; }
  LoopStats& stats() { return stats_; }
  int64_t restarts() const { return restarts_; }

 private:
  void apply_switch();
  bool handed_over(const JointData* j, Interface interface) const;
  void start(ControllerSlot& s);
  void stop(ControllerSlot& s);
  void fail_components(const hardware_state_t& st);
  void fail_controller(ControllerSlot& s);
  // Stops every running controller that writes `s`'s reference interfaces, and theirs in turn, naming `cause`.
  void stop_writers_of(const ControllerSlot& s, const ControllerSlot& cause);
  // Its update (when running and due) with the cycle's period; `mark`: the clock read that ended the last update.
  void update(ControllerSlot& s, const hardware_state_t& st, double period, int64_t& mark);
  // Its update_rate: whether it is due in this cycle, and then the period since its last update.
  bool due(ControllerSlot& s, const hardware_state_t& st, double period, double* own_period);
  void update_async(ControllerSlot& s, bool due, double own_period, bool here);
  void take_async(ControllerSlot& s);
  // starting(), stopping() or restart() of an async controller: here when its thread is idle, else before its next
  // update.
  void call_async(ControllerSlot& s, AsyncUpdate::Call call);
  bool claims_free(const ControllerSlot& s) const;
  // Each chainable controller's chained mode: whether a running controller now owns one of its reference interfaces.
  void chain_modes();

  Hardware& hw_;
  BeforeUpdate* before_update_ = nullptr;
  std::vector<std::unique_ptr<ControllerSlot>> slots_;
  std::vector<ControllerSlot*> order_;  // reorder()
  std::vector<ControllerSlot*> pending_stop_, pending_start_;
  bool pending_ = false;
  int pending_component_ = -1;
  Lifecycle pending_component_state_ = Lifecycle::Active;
  bool have_state_ = false, restart_ = false, e_stop_ = false;
  int64_t session_ = 0, step_ = -1, last_switch_step_ = -1, restarts_ = 0;
  Time now_;
  LoopStats stats_;
};

}  // namespace lcm_control::cm
