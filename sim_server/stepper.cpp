#include "sim_server/stepper.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

namespace lcm_control::sim {

namespace {
constexpr int64_t kMaxWaitSliceUs = 50000;  // check the stop flag at least this often
constexpr int64_t kStatsPeriodUs = 1000000;
// Real time: after a stall shorter than this the steps run back to back until sim time has caught up with
// the wall clock; after a longer one (a suspended machine) the missed steps are skipped and counted.
constexpr int64_t kMaxCatchUpUs = 500000;
}  // namespace

Stepper::Stepper(Simulation& sim, SimIo& io, const StepperOptions& options)
    : sim_(sim), io_(io), opt_(options), period_us_(sim.control_period() * 1e6) {}

bool Stepper::run(const std::atomic<bool>& stop) {
  start_us_ = monotonic_us();
  start_step_ = sim_.step_count();
  w_ = Window{};
  w_.start_us = start_us_;
  w_.start_step = start_step_;
  return opt_.lockstep ? run_lockstep(stop) : run_real_time(stop);
}

bool Stepper::done() const { return opt_.duration_s > 0 && sim_.time() >= opt_.duration_s - 1e-9; }

double Stepper::real_time_factor() const {
  const int64_t wall = monotonic_us() - start_us_;
  return wall > 0 ? double(sim_.step_count() - start_step_) * period_us_ / double(wall) : 0.0;
}

void Stepper::step_timed(int64_t deadline_us) {
  const int64_t t0 = monotonic_us();
  if (last_cycle_us_ >= 0) {
    const double period = double(t0 - last_cycle_us_);
    w_.period_min = w_.periods == 0 ? period : std::min(w_.period_min, period);
    w_.period_max = std::max(w_.period_max, period);
    w_.period_sum += period;
    w_.period_sq += period * period;
    ++w_.periods;
  }
  last_cycle_us_ = t0;
  sim_.step();
  const int64_t t1 = monotonic_us();
  io_.publish_state(real_time_factor());
  const int64_t t2 = monotonic_us();
  ++w_.cycles;
  w_.step_sum += double(t1 - t0);
  w_.step_max = std::max(w_.step_max, double(t1 - t0));
  w_.publish_sum += double(t2 - t1);
  w_.publish_max = std::max(w_.publish_max, double(t2 - t1));
  if (deadline_us > 0 && t2 > deadline_us) ++w_.overruns;
}

bool Stepper::run_lockstep(const std::atomic<bool>& stop) {
  const int64_t timeout_us = std::max<int64_t>(1000, std::llround(opt_.lockstep_timeout_s * 1e6));
  io_.publish_state(real_time_factor());
  while (!stop && !done()) {
    io_.expect_step(sim_.step_count());
    int64_t published = monotonic_us();
    bool said = false;
    while (!io_.has_command()) {
      if (stop) return true;
      const int64_t now = monotonic_us();
      if (now - published >= timeout_us) {
        io_.publish_state(real_time_factor());
        published = now;
        ++w_.missed;
        if (!said)
          spdlog::info("lockstep: waiting for the hardware/command of step {} (session {}); hardware/state is "
                       "republished every {:g} s, sim time stands still",
                       sim_.step_count(), io_.session(), opt_.lockstep_timeout_s);
        said = true;
      }
      tick_statistics(now);
      if (!io_.poll_until(std::min({published + timeout_us, now + kMaxWaitSliceUs, w_.start_us + kStatsPeriodUs}),
                          true))
        return false;
    }
    if (said) spdlog::info("lockstep: command for step {} arrived; stepping", sim_.step_count());
    io_.take_command();
    step_timed(0);
    tick_statistics(monotonic_us());
  }
  return true;
}

void Stepper::watchdog(int64_t now) {
  const int64_t last = io_.last_command_us();
  const bool lost = last >= 0 && double(now - last) > opt_.watchdog_s * 1e6;
  if (lost == watchdog_holding_) return;
  watchdog_holding_ = lost;
  sim_.actuators().set_hold_all(lost);
  if (lost)
    spdlog::warn("no hardware/command for {:g} ms (watchdog): every actuator holds at step {}", opt_.watchdog_s * 1e3,
                 sim_.step_count());
  else
    spdlog::info("hardware/command is back at step {}: commands apply again", sim_.step_count());
}

bool Stepper::run_real_time(const std::atomic<bool>& stop) {
  int64_t base_us = start_us_, base_step = sim_.step_count();
  io_.publish_state(1.0);
  while (!stop && !done()) {
    const int64_t deadline = base_us + std::llround(double(sim_.step_count() + 1 - base_step) * period_us_);
    int64_t now = monotonic_us();
    do {  // at least one pass, so messages are handled even while catching up
      if (stop) return true;
      tick_statistics(now);
      if (!io_.poll_until(std::min({deadline, now + kMaxWaitSliceUs, w_.start_us + kStatsPeriodUs}))) return false;
      now = monotonic_us();
    } while (now < deadline);
    const int64_t late = now - deadline;
    if (late > std::max<int64_t>(kMaxCatchUpUs, std::llround(10 * period_us_))) {
      w_.missed += std::llround(double(late) / period_us_);
      base_us = now;
      base_step = sim_.step_count();
    }
    if (!io_.take_command() && io_.last_command_us() >= 0) ++w_.missed;  // the controller did not answer in time
    watchdog(now);
    step_timed(deadline + std::llround(period_us_));
    tick_statistics(monotonic_us());
  }
  return true;
}

void Stepper::tick_statistics(int64_t now) {
  if (now - w_.start_us < kStatsPeriodUs) return;
  loop_stats_t s;
  s.utime = sim_.time_us();
  s.process = "sim_server";
  s.cycles = w_.cycles;
  const double periods = double(std::max<int64_t>(1, w_.periods));
  s.period_mean_us = w_.period_sum / periods;
  s.period_min_us = w_.period_min;
  s.period_max_us = w_.period_max;
  s.period_jitter_us = std::sqrt(std::max(0.0, w_.period_sq / periods - s.period_mean_us * s.period_mean_us));
  s.overruns = w_.overruns;
  s.missed = w_.missed;
  s.dropped = io_.dropped() - w_.dropped_before;
  s.real_time_factor = double(sim_.step_count() - w_.start_step) * period_us_ / double(now - w_.start_us);
  const double cycles = double(std::max<int64_t>(1, w_.cycles));
  s.exec_mean_us = (w_.step_sum + w_.publish_sum) / cycles;
  s.exec_max_us = w_.step_max + w_.publish_max;
  s.num_items = 2;
  s.item = {"step", "publish"};
  s.item_exec_mean_us = {w_.step_sum / cycles, w_.publish_sum / cycles};
  s.item_exec_max_us = {w_.step_max, w_.publish_max};
  io_.publish_statistics(s);
  const int64_t dropped = io_.dropped();
  w_ = Window{};
  w_.start_us = now;
  w_.start_step = sim_.step_count();
  w_.dropped_before = dropped;
}

}  // namespace lcm_control::sim
