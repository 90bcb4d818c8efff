#include "sim_server/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "description/model_check.hpp"

namespace lcm_control::sim {

int substeps_for(const SimulationRates& r) {
  if (!(r.physics_hz > 0) || !(r.control_hz > 0) || !std::isfinite(r.physics_hz) || !std::isfinite(r.control_hz))
    throw std::invalid_argument(
        fmt::format("--physics-rate {:g} and --control-rate {:g} must be positive", r.physics_hz, r.control_hz));
  const double ratio = r.physics_hz / r.control_hz;
  const long n = std::lround(ratio);
  if (n < 1 || std::abs(ratio - double(n)) > 1e-9 * ratio)
    throw std::invalid_argument(fmt::format("--physics-rate {:g} Hz must be a whole multiple of --control-rate {:g} Hz",
                                            r.physics_hz, r.control_hz));
  return int(n);
}

int clock_every_for(double control_hz, double clock_hz) {
  if (!(clock_hz >= 0) || !std::isfinite(clock_hz))
    throw std::invalid_argument(
        fmt::format("--clock-rate {:g} must be 0 (every control step) or a positive rate in Hz", clock_hz));
  if (clock_hz == 0) return 1;
  return int(std::max(1L, std::lround(control_hz / clock_hz)));
}

Simulation::Simulation(const RobotModel& model, const SimulationRates& rates, const InitialPositions& initial,
                       const WorldOptions& world, Backend backend)
    : model_(model),
      initial_(initial),
      world_(world),
      gpio_(model_),
      components_(model_),
      control_period_(1.0 / rates.control_hz),
      control_hz_(rates.control_hz),
      substeps_(substeps_for(rates)) {
  if (backend == Backend::Mock) {
    mock_ = std::make_unique<MockHardware>(model_, initial_);
    return;
  }
  if (const std::string why = simulation_size_problem(model_); !why.empty()) throw ModelError(why);
  multibody_ = std::make_unique<Multibody>(model_, 1.0 / rates.physics_hz, initial_, world_);
  actuators_ = std::make_unique<Actuators>(model_, *multibody_);
  multibody_->size_solver_buffers();
  actuators_->read(multibody_->dt());
  sensors_ = std::make_unique<SensorBank>(model_, *multibody_, world_.noise_seed);
}

std::vector<std::string> Simulation::reset(const InitialPositions& changes) {
  InitialPositions initial = initial_;
  for (const auto& [joint, q] : changes) initial[joint] = q;
  gpio_.reset();
  if (mock_) {
    auto mock = std::make_unique<MockHardware>(model_, initial);
    mock->set_hold_all(mock_->hold_all());
    mock->set_e_stop(mock_->e_stop());
    mock_ = std::move(mock);
    initial_ = std::move(initial);
    steps_ = 0;
    return mock_->start_warnings();
  }
  auto multibody = std::make_unique<Multibody>(model_, multibody_->dt(), initial, world_);
  auto actuators = std::make_unique<Actuators>(model_, *multibody);
  for (int i = 0; i < actuators->size(); ++i)
    if (actuators->has_pid(i)) actuators->set_gains(i, actuators_->gains(i));
  actuators->set_brakes(actuators_->brakes());
  actuators->set_hold_all(actuators_->hold_all());
  multibody->size_solver_buffers();
  actuators->read(multibody->dt());
  actuators->set_e_stop(actuators_->e_stop());
  auto sensors = std::make_unique<SensorBank>(model_, *multibody, world_.noise_seed);
  actuators_ = std::move(actuators);  // before the multibody they refer to
  sensors_ = std::move(sensors);
  multibody_ = std::move(multibody);
  initial_ = std::move(initial);
  steps_ = 0;
  wrenches_.clear();
  return multibody_->start_warnings();
}

std::string Simulation::apply_wrench(const std::string& link, const Eigen::Vector3d& force,
                                     const Eigen::Vector3d& torque, double duration_s) {
  if (mock_) return "mock hardware has no physics to push (run the robot in Bullet: sim_server --physics)";
  if (!force.allFinite() || !torque.allFinite() || !std::isfinite(duration_s))
    return "the force, torque and duration must be finite numbers";
  int index = -1;
  try {
    index = multibody_->link_index(link);
  } catch (const std::out_of_range&) {
    std::string links;
    for (const Link& l : model_.links) links += (links.empty() ? "" : ", ") + l.name;
    return fmt::format("no link '{}' in {} (its links: {})", link, model_.urdf_path, links);
  }
  wrenches_.reserve(model_.links.size());  // one per link at most: steps never grow it
  wrenches_.erase(std::remove_if(wrenches_.begin(), wrenches_.end(), [&](const Wrench& w) { return w.index == index; }),
                  wrenches_.end());
  if (duration_s == 0) return "";
  const int64_t until = duration_s < 0 ? -1 : steps_ + std::max<int64_t>(1, std::llround(duration_s * control_hz_));
  wrenches_.push_back({index, force, torque, until});
  return "";
}

const std::vector<std::string>& Simulation::start_warnings() const {
  return mock_ ? mock_->start_warnings() : multibody_->start_warnings();
}

std::vector<std::string> Simulation::describe() const {
  std::vector<std::string> lines;
  for (int i = 0; i < hardware().size(); ++i) lines.push_back(mock_ ? mock_->describe(i) : actuators_->describe(i));
  return lines;
}

std::vector<std::string> Simulation::warnings() const {
  std::vector<std::string> lines;
  if (multibody_) {
    lines = multibody_->warnings();
    lines.insert(lines.end(), actuators_->warnings().begin(), actuators_->warnings().end());
  }
  lines.insert(lines.end(), start_warnings().begin(), start_warnings().end());
  return lines;
}

std::vector<std::string> Simulation::notes() const {
  return multibody_ ? multibody_->start_notes() : std::vector<std::string>{};
}

void Simulation::step() {
  if (mock_) {
    mock_->step(control_period_);
    ++steps_;
    return;
  }
  const double dt = multibody_->dt();
  for (size_t w = 0; w < wrenches_.size();)  // erase keeps the capacity: no allocation
    if (wrenches_[w].until_step >= 0 && steps_ >= wrenches_[w].until_step)
      wrenches_.erase(wrenches_.begin() + std::ptrdiff_t(w));
    else
      ++w;
  sensors_->clear_external_wrenches();
  for (const Wrench& w : wrenches_) sensors_->add_external_wrench(w.index, w.force, w.torque);
  for (int s = 0; s < substeps_; ++s) {
    for (const Wrench& w : wrenches_) multibody_->add_link_wrench(w.index, w.force, w.torque);
    actuators_->apply(dt);
    multibody_->step();
    actuators_->read(dt);
    sensors_->update();
  }
  ++steps_;
}

int64_t Simulation::time_us() const { return std::llround(double(steps_) * 1e6 / control_hz_); }

}  // namespace lcm_control::sim
