#include "tools/lib/logs/closed_loop.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <stdexcept>

#include "bus/messages.hpp"
#include "description/load.hpp"
#include "rt/clock.hpp"

namespace lcm_control::tools {

namespace {
// A program's flags (added by add_flags) from its command line.
template <class Flags, class Add>
Flags parse_command_line(const std::vector<std::string>& argv, Add add_flags) {
  Flags flags;
  CLI::App app;
  add_flags(app, flags);
  std::vector<std::string> args(argv.begin() + (argv.empty() ? 0 : 1), argv.end());
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return flags;
}
}  // namespace

sim::ProgramFlags parse_sim_command_line(const std::vector<std::string>& argv) {
  return parse_command_line<sim::ProgramFlags>(argv, sim::add_program_flags);
}

cm::ProgramFlags parse_manager_command_line(const std::vector<std::string>& argv) {
  return parse_command_line<cm::ProgramFlags>(argv, cm::add_program_flags);
}

namespace {
cm::Registry registry_for(const RobotModel& model) {
  cm::Registry registry = cm::builtin_registry();
  cm::load_plugins(registry, cm::plugin_libraries(model));
  return registry;
}
}  // namespace

ReplayedManager::ReplayedManager(const RobotModel& model, Bus& b, cm::ManagerOptions options)
    : bus(b), registry(registry_for(model)), manager(model, bus, registry, std::move(options)), services(manager, bus) {
  bus.lcm().subscribe(bus.channel(channels::kJointStates), &ReplayedManager::on_joint_states, this);
}

ReplayedManager::~ReplayedManager() { manager.shutdown(); }

void ReplayedManager::on_joint_states(const lcm::ReceiveBuffer*, const std::string&, const joint_state_t* m) {
  joint_states.push_back(*m);
}

void ReplayedManager::pump() {
  for (bool more = true; more;) {
    manager.flush_published();
    more = false;
    while (bus.lcm().handleTimeout(0) > 0) more = true;
  }
}

ClosedLoop::ClosedLoop(const sim::ProgramFlags& flags, const LoadOptions& sim_load, const RobotModel& model,
                       cm::ManagerOptions manager_options)
    : sim_model_(load_robot_model(flags.robot.files.urdf, flags.robot.files.config, sim_load)),
      plan_(sim::plan_run(flags, sim_model_)),
      simulation_(std::make_unique<sim::Simulation>(sim_model_, plan_.rates, plan_.start, plan_.world,
                                                    plan_.mock ? sim::Backend::Mock : sim::Backend::Bullet)),
      bus_("memq://", model.ns) {
  if (!plan_.mock) simulation_->actuators().set_brakes(plan_.brakes);
  io_ = std::make_unique<sim::SimIo>(bus_, *simulation_, true, plan_.clock_every);
  manager_ = std::make_unique<ReplayedManager>(model, bus_, std::move(manager_options));
}

double ClosedLoop::control_period_s() const { return simulation_->control_period(); }

const hardware_command_t& ClosedLoop::cycle() {
  io_->expect_step(step());
  io_->publish_state(1.0);
  manager_->pump();
  return manager_->manager.last_command();
}

void ClosedLoop::advance() {
  if (std::exchange(reset_, false) || paused_) return;
  if (!io_->poll_until(monotonic_us(), true, false, step()) || !io_->take_command())
    throw std::runtime_error(fmt::format("closed loop: no command for step {}", step()));
  simulation_->step();
}

sim_response_t ClosedLoop::serve(const sim_request_t& req) {
  sim_response_t a{};
  a.request_id = req.request_id;
  a.op = req.op;
  a.ok = true;
  sim::Simulation& sim = *simulation_;
  if (req.op == sim_request_t::APPLY_WRENCH) {
    a.message = sim.apply_wrench(req.link, {req.force.x, req.force.y, req.force.z},
                                 {req.torque.x, req.torque.y, req.torque.z}, req.duration);
    a.ok = a.message.empty();
    if (a.ok) a.message = fmt::format("applying the wrench on '{}' for {:g} s of sim time", req.link, req.duration);
  } else if (req.op == sim_request_t::PAUSE || req.op == sim_request_t::RESUME) {
    paused_ = req.op == sim_request_t::PAUSE;  // paused: the state is republished, sim time holds
  } else if (req.op == sim_request_t::RESET) {
    InitialPositions changes;
    const size_t n = std::min({size_t(std::max(req.num_joints, 0)), req.joint.size(), req.position.size()});
    for (size_t j = 0; j < n; ++j) changes[req.joint[j]] = req.position[j];
    const int64_t previous = sim.step_count();
    try {
      for (const std::string& clamped : sim.reset(changes)) a.message += clamped + "; ";
      io_->after_reset(previous);
      reset_ = true;
      ++resets_;  // the next cycle publishes step 0; the answer to the last one is void
    } catch (const ModelError& e) {
      a.ok = false;
      a.message = fmt::format("cannot reset: {}", e.what());
    }
  } else {
    a.ok = false;
    a.message = fmt::format("served here: wrenches, pauses and resets; not sim_request_t op {}", int(req.op));
  }
  a.utime = sim.time_us();
  a.paused = paused_;
  a.lockstep = true;
  a.step = sim.step_count();
  a.period_us = int32_t(std::llround(sim.control_period() * 1e6));
  a.resets = resets_;
  return a;
}

}  // namespace lcm_control::tools
