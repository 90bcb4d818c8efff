// The simulated robot in one object: the multibody and its actuators (or, for
// Backend::Mock, mock hardware without physics), advanced one control period
// (one or more physics steps) at a time, and put back to its start by reset().
// step() is the real-time path: no allocation, logging, locks or wall-clock
// input.
#pragma once

#include <Eigen/Core>

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "description/robot_model.hpp"
#include "sim_server/actuators.hpp"
#include "sim_server/components.hpp"
#include "sim_server/gpio.hpp"
#include "sim_server/mock_hardware.hpp"
#include "sim_server/multibody_builder.hpp"
#include "sim_server/sensors.hpp"

namespace lcm_control::sim {

struct SimulationRates {
  double physics_hz = 1000;
  double control_hz = 1000;  // physics_hz must be a whole multiple of it
};

// Physics steps per control step; throws std::invalid_argument unless physics_hz is a whole multiple of control_hz.
int substeps_for(const SimulationRates& rates);

// Control steps per `clock` message for a wanted clock rate in sim-time Hz: the nearest whole number, at least 1;
// 0 means every control step. Throws std::invalid_argument for a negative or non-finite rate.
int clock_every_for(double control_hz, double clock_hz);

// Bullet: the multibody and its actuators. Mock: mock_components/GenericSystem's state-follows-command, one update
// per control step, no physics (world options and the physics rate do not apply).
enum class Backend { Bullet, Mock };

class Simulation {
 public:
  // Throws ModelError for a robot Bullet cannot take or a bad initial position, std::invalid_argument for bad
  // rates.
  Simulation(const RobotModel& model, const SimulationRates& rates, const InitialPositions& initial = {},
             const WorldOptions& world = {}, Backend backend = Backend::Bullet);

  // One control period: substeps() times (actuators -> physics step -> read back).
  void step();

  // Back to the state the constructor made (a floating base too): the multibody and its actuators are built afresh
  // from the model (so a
  // run after a reset repeats the first one bit for bit), at the initial positions with `changes` merged into them
  // (kept for later resets); step and sim time 0. What the user set since the start carries over: PID gains, brakes,
  // e-stop (still latched: it holds the new pose). Returns the start positions clamped into the limits (one line
  // each). Throws ModelError for a change naming no moving joint or not finite; nothing changes then. References
  // from multibody() and actuators() do not survive it.
  std::vector<std::string> reset(const InitialPositions& changes = {});
  const InitialPositions& initial_positions() const { return initial_; }

  int64_t step_count() const { return steps_; }                  // control steps taken
  int64_t time_us() const;                                       // sim time of step_count()
  double time() const { return double(steps_) * control_period_; }
  double physics_dt() const { return multibody_ ? multibody_->dt() : control_period_; }
  double control_period() const { return control_period_; }
  int substeps() const { return multibody_ ? substeps_ : 1; }

  Backend backend() const { return mock_ ? Backend::Mock : Backend::Bullet; }
  bool floating_base() const { return multibody_ && multibody_->floating_base(); }
  // What the LCM side drives, either backend.
  PlayedHardware& hardware() { return mock_ ? static_cast<PlayedHardware&>(*mock_) : *actuators_; }
  const PlayedHardware& hardware() const { return mock_ ? static_cast<const PlayedHardware&>(*mock_) : *actuators_; }
  // Backend::Bullet only.
  Multibody& multibody() { return *multibody_; }
  Actuators& actuators() { return *actuators_; }
  const Actuators& actuators() const { return *actuators_; }
  // The declared sensors, measured after every physics step (Backend::Bullet; none for Mock).
  const SensorBank* sensors() const { return sensors_.get(); }
  // Backend::Mock only.
  MockHardware& mock() { return *mock_; }
  // The <gpio> interfaces, either backend (a reset puts them back at their initial values).
  GpioBank& gpio() { return gpio_; }
  const GpioBank& gpio() const { return gpio_; }
  // Gazebo's apply_body_wrench: `force` (N) at `link`'s centre of mass and `torque` (N*m), world frame, on every
  // physics step for `duration_s` of sim time (< 0: until replaced or cleared; 0: clears the link's wrench). One
  // wrench per link, replaced by the next; a reset clears them. Returns "" or why not (no such link, mock hardware).
  std::string apply_wrench(const std::string& link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
                           double duration_s);
  // The hardware components' lifecycle as the controller manager sets it (kept across resets).
  ComponentStates& components() { return components_; }
  // Start positions clamped into the limits, one line each.
  const std::vector<std::string>& start_warnings() const;
  // One INFO line per actuator: how it plays its modes.
  std::vector<std::string> describe() const;
  // The WARN lines of building it: the multibody's and actuators' findings, then start_warnings().
  std::vector<std::string> warnings() const;
  // The INFO lines of building it (a floating base lifted out of the ground).
  std::vector<std::string> notes() const;

 private:
  RobotModel model_;  // the multibody points into it
  InitialPositions initial_;
  WorldOptions world_;
  std::unique_ptr<Multibody> multibody_;
  std::unique_ptr<Actuators> actuators_;
  std::unique_ptr<SensorBank> sensors_;
  std::unique_ptr<MockHardware> mock_;
  GpioBank gpio_;
  ComponentStates components_;
  double control_period_;
  double control_hz_;
  int substeps_;
  int64_t steps_ = 0;
  struct Wrench {
    int index = -1;  // Bullet link
    Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
    int64_t until_step = -1;  // the control step it ends at (-1: never)
  };
  std::vector<Wrench> wrenches_;
};

}  // namespace lcm_control::sim
