#include "sim_server/simulation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "common/substitution.hpp"
#include "common/text.hpp"

namespace lcm_control::sim {

std::pair<std::string, double> parse_initial_position(const std::string& assignment) {
  const auto [name, text] = parse_arg(assignment);
  double value = 0;
  if (!parse_double(text, value))
    throw std::invalid_argument(fmt::format("initial position '{}': '{}' is not a number; write JOINT=VALUE in rad "
                                            "(or m), e.g. {}=-1.57",
                                            assignment, text, name));
  return {name, value};
}

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

Simulation::Simulation(const RobotModel& model, const SimulationRates& rates, const InitialPositions& initial)
    : control_period_(1.0 / rates.control_hz), control_hz_(rates.control_hz), substeps_(substeps_for(rates)) {
  multibody_ = std::make_unique<Multibody>(model, 1.0 / rates.physics_hz, initial);
  actuators_ = std::make_unique<Actuators>(model, *multibody_);
  multibody_->size_solver_buffers();
  actuators_->read(multibody_->dt());
}

void Simulation::step() {
  const double dt = multibody_->dt();
  for (int s = 0; s < substeps_; ++s) {
    actuators_->apply(dt);
    multibody_->step();
    actuators_->read(dt);
  }
  ++steps_;
}

int64_t Simulation::time_us() const { return std::llround(double(steps_) * 1e6 / control_hz_); }

}  // namespace lcm_control::sim
