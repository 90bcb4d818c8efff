// sim_server's simulation and a fresh controller manager in one process, on an in-process bus (memq://), stepped in
// lockstep as the two programs step each other over LCM: state k published, the manager's answer to it taken, the
// physics stepped. What `replay --sim` re-runs a recording with and what a scenario runs; nothing in either program
// changes for it.
#pragma once

#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "controller_manager/manager.hpp"
#include "controller_manager/plugins.hpp"
#include "controller_manager/program.hpp"
#include "controller_manager/services.hpp"
#include "description/robot_model.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "lcm_control/sim_response_t.hpp"
#include "sim_server/program.hpp"
#include "sim_server/sim_io.hpp"
#include "sim_server/simulation.hpp"

namespace lcm_control::tools {

// sim_server's and controller_manager's flags from their command lines (argv[0] first, as run_config_t records
// them); throw CLI::ParseError.
sim::ProgramFlags parse_sim_command_line(const std::vector<std::string>& argv);
cm::ProgramFlags parse_manager_command_line(const std::vector<std::string>& argv);

// A controller manager on a bus with its services, keeping the joint_states it publishes: what both replays re-drive.
struct ReplayedManager {
  ReplayedManager(const RobotModel& model, Bus& bus, cm::ManagerOptions options = {});
  ~ReplayedManager();  // it answers what is pending while the services that answer are there
  // Delivers what is queued on the bus, and what handling it publishes, until nothing is left.
  void pump();
  Bus& bus;
  cm::Registry registry;
  cm::ControllerManager manager;
  cm::Services services;
  std::deque<joint_state_t> joint_states;  // published, oldest first; a reader pops what it has used
  void on_joint_states(const lcm::ReceiveBuffer*, const std::string&, const joint_state_t* m);
};

class ClosedLoop {
 public:
  // The simulation as sim_server builds it from `flags` (its files read with `sim_load`), the manager from `model`
  // (`manager_options.command_line` is what it records as its own). Throws ModelError, std::invalid_argument or
  // CLI::ValidationError as sim_server and the manager would refuse them.
  ClosedLoop(const sim::ProgramFlags& flags, const LoadOptions& sim_load, const RobotModel& model,
             cm::ManagerOptions manager_options = {});

  Bus& bus() { return bus_; }
  sim::Simulation& simulation() { return *simulation_; }
  sim::SimIo& io() { return *io_; }
  ReplayedManager& manager() { return *manager_; }
  const RobotModel& sim_model() const { return sim_model_; }
  double control_period_s() const;
  int64_t step() const { return simulation_->step_count(); }  // the step whose state the next cycle publishes

  // Publishes the current step's state and lets the manager take in what is queued before it and answer; returns
  // its answer (the command it sent for this step).
  const hardware_command_t& cycle();
  // Hands the answer to the actuators and steps the physics; throws std::runtime_error when no answer came. Paused,
  // sim time holds (the next cycle republishes the state); after a reset, the next cycle publishes step 0.
  void advance();

  // A sim_server request (sim_server/request), served between a cycle and the step after it as sim_server's
  // Stepper serves it in lockstep: APPLY_WRENCH, PAUSE, RESUME and RESET; the others are refused. Returns the answer
  // (request id, op, ok, message, paused, step).
  sim_response_t serve(const sim_request_t& request);
  bool paused() const { return paused_; }

 private:
  RobotModel sim_model_;
  sim::RunPlan plan_;
  std::unique_ptr<sim::Simulation> simulation_;
  Bus bus_;
  std::unique_ptr<sim::SimIo> io_;
  std::unique_ptr<ReplayedManager> manager_;
  bool paused_ = false, reset_ = false;
  int64_t resets_ = 0;
};

}  // namespace lcm_control::tools
