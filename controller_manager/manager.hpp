// The controller manager without its LCM request plumbing: load / unload /
// switch / reload / list with ros_control semantics and replies that say what
// happened and why, the hardware side (session binding, silence, publishing
// the command) around the real-time Loop, and loop statistics.
#pragma once

#include <cstdint>
#include <functional>
#include <future>
#include <unordered_map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "controller_manager/arrival_clock.hpp"
#include "bus/bus.hpp"
#include "rt/intake.hpp"
#include "rt/outbox.hpp"
#include "rt/log.hpp"
#include "description/robot_model.hpp"
#include "controller_manager/command_sources.hpp"
#include "controller_manager/input_stamps.hpp"
#include "controller_manager/hardware.hpp"
#include "controller_manager/hardware_status.hpp"
#include "controller_manager/loop.hpp"
#include "controller_interface/registry.hpp"
#include "controller_manager/reply.hpp"
#include "lcm_control/activity_t.hpp"
#include "lcm_control/controller_info_t.hpp"
#include "lcm_control/hardware_component_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/joint_interfaces_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/run_config_t.hpp"
#include "controllers/builtin.hpp"

namespace lcm_control::cm {

// What loading one configured controller gives, found without loading it.
struct ControllerCheck {
  enum Outcome {
    Loads,
    NotImplemented,     // a known ROS type that is not built in here
    InterfaceMismatch,  // the URDF's transmissions do not offer what it claims (a YAML for another variant)
    Refused             // anything else: unknown type, missing or bad parameter, unknown joint
  };
  std::string name, type;
  Outcome outcome = Loads;
  std::string message;             // why it does not load
  std::vector<std::string> notes;  // parameters ignored and other findings, one line each
  double update_rate_hz = 0;       // its own update_rate (ROS 2), 0: every cycle of the manager
  std::vector<std::string> fallbacks;  // its fallback_controllers (ROS 2), started when it fails
  bool is_async = false;               // ROS 2's is_async: it updates on a thread of its own
};

struct ManagerOptions {
  int64_t silence_us = 250000;  // no hardware state for this long: the loop is not ticking
  // 0: every request's work is done when asked (tests). Otherwise the controller manager program's slice: a reload
  // reads the YAML on a worker thread and unloaded controllers are destroyed by poll() in slices this long.
  int64_t slice_us = 0;
  // Trajectory goals and other large messages decoded and planned on a thread of its own (rt/intake.hpp), except in
  // lockstep (the program). false: in the handler (tests).
  bool intake_thread = false;
  std::vector<std::string> command_line;  // the program's, for run_config_t
};

// A LOAD or UNLOAD of many names, served a few names at a time between cycles (step()); `reply` is final when
// step() returns true.
struct Batch {
  std::vector<std::string> names;
  bool load = true;
  Reply reply{true, ""};
  size_t next = 0, shown = 0, done = 0, refused = 0;  // names served; lines in the reply; beyond them, counted
  std::vector<std::string> unknown;
  size_t near_at = 0, near_distance = 4;  // the "did you mean" scan (within 3 edits) over the candidates, resumable too
  std::string near;
};

class ControllerManager {
 public:
  ControllerManager(RobotModel model, Bus& bus, const Registry& registry = builtin_registry(),
                    ManagerOptions options = {});
  ~ControllerManager();
  ControllerManager(const ControllerManager&) = delete;
  ControllerManager& operator=(const ControllerManager&) = delete;

  const RobotModel& model() const { return model_; }
  Hardware& hardware() { return hw_; }
  Loop& loop() { return loop_; }
  CommandSources& command_sources() { return sources_; }

  Reply load(const std::string& name);
  Reply unload(const std::string& name);
  // Each name in turn, in one reply; the names not configured (load) or not loaded (unload) are refused together in
  // one bounded sentence, however many there are.
  Reply load(const std::vector<std::string>& names) { return each(names, true); }
  Reply unload(const std::vector<std::string>& names) { return each(names, false); }
  // Serves `batch` until it is done (true) or monotonic_us() passes deadline_us (false: call again).
  bool step(Batch& batch, int64_t deadline_us);
  // Applied after the next update when hardware is ticking, at once otherwise;
  // `done` gets the reply when the switch has happened or was refused.
  void switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop, int strictness,
                          Done done);
  // Unloads everything (with force: stops the running ones first) and re-reads the config file.
  void reload(bool force, Done done);
  std::vector<controller_info_t> list() const;
  // The first loaded controllers, in load order, whose encoded size fits in max_bytes.
  std::vector<controller_info_t> list(size_t max_bytes) const;
  size_t loaded() const { return loop_.slots().size(); }
  // Every actuated joint's command and state interfaces and which running controller claims it.
  std::vector<joint_interfaces_t> interfaces() const;
  bool from_ros2() const { return model_.from_ros2(); }
  // Tries every configured controller without loading it (doctor, start-up).
  std::vector<ControllerCheck> check_configured();
  std::vector<std::string> types() const { return registry_.types(); }
  // What it was started with (run_config_t: the URDF as read, the YAML files' texts, the $(arg) values), published on
  // controller_manager/config so that a recording of the run replays on its own. The files are read (the xacro
  // expanded) at the first call, which the program makes at start, and again only after a reload; later calls
  // republish what was read. The reply says what was published, or why not (a file gone since).
  Reply publish_config();
  // Its declaration in one line: "ROS 2, chainable: <doc>" ("" for a type that declares nothing).
  std::string type_doc(const std::string& type) const;
  bool busy() const { return static_cast<bool>(pending_done_) || static_cast<bool>(reload_done_); }
  // Unloaded controllers poll() has still to destroy.
  bool has_work() const { return !retired_.empty(); }
  // A reload's YAML is being read on the worker thread: poll() finishes the reload when it is read.
  bool reading_config() const { return reload_read_.valid(); }
  // Goals are being prepared off the loop, or wait to be taken by poll().
  bool taking_in() const { return intake_ && intake_->busy(); }

  // One hardware/state message (already checked): bind, cycle, publish the command.
  void on_hardware_state(const hardware_state_t& state);
  // Housekeeping between messages: silence (no hardware/state for silence_us,
  // whatever else arrives; call it with the receive queue drained, so that a
  // state waiting in it is not mistaken for silence), a pending switch without
  // hardware, statistics at 1 Hz.
  void poll(int64_t monotonic_now_us);
  bool ticking() const { return loop_.has_state() && !silent_; }
  // The hardware this manager follows, one line (HardwareStatus::describe), and the age of its last state (-1: none).
  std::string hardware_summary(int64_t monotonic_now_us) const;
  int64_t hardware_age_us(int64_t monotonic_now_us) const { return hw_status_.age_us(monotonic_now_us); }
  void count_dropped(int64_t n) { dropped_ += n; }
  // When the next hardware/state is expected in real time, from the states taken so far (--spin-us sleeps to it).
  const ArrivalClock& state_arrivals() const { return arrivals_; }
  const hardware_command_t& last_command() const { return command_; }

  // Hardware components (ros2_control's lifecycle; hardware_lifecycle.cpp). A component leaving active stops the
  // running controllers that command it, leaving inactive those that read it too, in the cycle it changes (at once
  // when the hardware is silent); `done` gets the reply then.
  void set_component_state(const std::string& name, Lifecycle target, Done done);
  std::vector<hardware_component_t> components() const;
  activity_t activity() const;

  loop_stats_t statistics();  // the current window, then a new one
  // Waits until the controllers' messages handed over so far have left (tests; not for the loop path).
  void flush_published();
  // Between cycles: what arrived for is_async controllers while their update ran (Endpoints::hold_while) is delivered
  // to those whose thread is idle.
  void deliver_held();
  // Stops and unloads every controller; returns what was done.
  std::string shutdown();

 private:
  // The run's configuration as publish_config read it; "" or why it could not be read.
  std::string read_run_config();
  std::optional<run_config_t> run_config_;  // read once, again after a reload
  ControllerSlot* find(const std::string& name) const;
  // Creates and initialises a controller of `spec` on `port`; on success moves it to *out (if given).
  // With `out`, the controller made; an is_async one is initialised on a Hardware of its own, given in `shadow`.
  // checking: only trying it (doctor, start-up): a reference interface it claims need only be configured.
  ControllerCheck instantiate(const ControllerSpec& spec, Endpoints& endpoints, std::unique_ptr<Controller>* out,
                              std::unique_ptr<Hardware>* shadow = nullptr, bool checking = false);
  // A ROS 2 controller's own `update_rate` (Hz), checked against the manager's; throws ControllerError.
  double own_update_rate(const Params& params) const;
  std::string yaml_key(const std::string& controller) const;  // its key path in the YAML
  void complete_pending();
  // "" when the components `s` uses let it start; else why not and what to do.
  std::string unfit_to_start(const ControllerSlot& s) const;
  // ROS 2's fallback_controllers of `name`: configured controllers other than itself; throws ControllerError.
  std::vector<std::string> fallback_controllers(const std::string& name, const Params& params) const;
  // Logs each controller that failed in this cycle, once, with the fallbacks started (hardware_lifecycle.cpp).
  void report_failed_controllers();
  // "; and the controllers chained above it [a, b] (they write its reference interfaces: a chain runs whole)" for
  // those the loop stopped with `cause` (nullptr: any), clearing their mark; "" for none.
  std::string take_chain_stops(const ControllerSlot* cause);
  // Logs each component error the loop took in this cycle, once, with the hardware's reason and what stopped.
  void report_component_errors(const hardware_state_t& st);
  void changed() {  // a controller or component changed state: activity is published at the next poll()
    ++activity_seq_;
    activity_step_ = loop_.has_state() ? loop_.step() : -1;
    activity_due_ = true;
  }
  std::string names_loaded() const;
  std::string names_configured() const;  // the first 20, then "(and N more)"
  Reply each(const std::vector<std::string>& names, bool load);
  static std::unordered_map<std::string, size_t> index_of(const std::vector<ControllerSpec>& controllers);
  // Out of the loop; destroyed now, or by poll() in slices.
  void retire(std::unique_ptr<ControllerSlot> slot);
  // A reload's config as read: the model, or why not; the index of its controllers by name.
  struct ReadConfig {
    RobotModel model;
    std::string error;
    std::unordered_map<std::string, size_t> index;
  };
  void finish_reload(ReadConfig read);

  RobotModel model_;
  Bus& bus_;
  const Registry& registry_;
  ManagerOptions options_;
  // What the controllers publish leaves from here, not from the loop thread; declared before the controllers so
  // that it outlives them and sends what they publish when stopped.
  std::unique_ptr<lcm::LCM> outbox_lcm_;
  Outbox outbox_;
  std::unique_ptr<Intake> intake_;  // outlives the controllers, whose endpoints hand it their goals
  Hardware hw_;
  Loop loop_;
  std::vector<std::unique_ptr<ControllerSlot>> retired_;  // unloaded, not destroyed yet (slice_us > 0)
  Endpoints endpoints_;
  Endpoints hw_endpoints_;  // hardware/state and hardware/command: the bus's hardware loop
  CommandSources sources_;
  hardware_command_t command_{};
  Publisher<hardware_command_t> command_pub_;
  Publisher<loop_stats_t> stats_pub_;
  Publisher<activity_t> activity_pub_;
  InputStamps inputs_;  // what each cycle took in from the shared bus, for replay
  int64_t activity_seq_ = 0, activity_step_ = -1, last_activity_us_ = 0;
  bool activity_due_ = true;
  bool pending_component_ = false;  // the pending switch is a component's state change
  Done pending_done_;
  std::unordered_map<std::string, size_t> configured_;  // name -> model_.controllers index
  // A reload whose YAML a worker thread reads: its answer, what it unloads, and the result (an error or the model).
  Done reload_done_;
  std::vector<std::string> reload_unloaded_;
  std::future<ReadConfig> reload_read_;
  std::future<void> disposal_;  // the controllers a reload replaced, destroyed on a worker thread
  bool shutting_down_ = false;  // from shutdown() on, switches and reloads are refused
  BusLog hardware_log_;         // session lines: a peer can send a new session with every message
  HardwareStatus hw_status_;
  ArrivalClock arrivals_;
  std::string pending_summary_;
  int64_t last_state_us_ = 0, last_stats_us_ = 0, bad_session_ = 0, dropped_ = 0, bad_state_logged_ = 0,
          reported_dropped_ = 0, reported_unpublished_ = 0;
  bool silent_ = false;
  // The newest state of a session ignored while the followed one counted as alive: reported as a second simulator
  // if the followed one speaks again, else answered as soon as it falls silent, so a simulator started right after
  // another ended (a sweep) does not wait until it republishes (lockstep: every --lockstep-timeout, 1 s).
  hardware_state_t waiting_{};
  bool has_waiting_ = false;
};

}  // namespace lcm_control::cm
