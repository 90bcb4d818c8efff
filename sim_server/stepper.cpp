#include "sim_server/stepper.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "rt/log.hpp"

namespace lcm_control::sim {

namespace {
constexpr int64_t kMaxWaitSliceUs = 50000;  // check the stop flag at least this often
constexpr int64_t kStatsPeriodUs = 1000000;
// Real time: after a stall shorter than this the steps run back to back until sim time has caught up with
// the wall clock; after a longer one (a suspended machine) the missed steps are skipped and counted.
constexpr int64_t kMaxCatchUpUs = 500000;
// Paused: the state is republished this often, below the controller manager's default silence timeout (0.25 s), so
// that it keeps following the hardware and applies switches on the repeated state.
constexpr int64_t kPausedRepublishUs = 100000;
}  // namespace

Stepper::Stepper(Simulation& sim, SimIo& io, const StepperOptions& options)
    : sim_(sim), io_(io), opt_(options), period_us_(sim.control_period() * 1e6), paused_(options.start_paused) {
  step_request_.request_id = 0;
  const size_t n = sim.components().components().size();
  component_ns_.assign(n, 0);
  component_exec_.resize(n);
  component_period_.resize(n);
  component_has_actuators_.assign(n, 0);
  for (const int c : sim.components().component_of())
    if (c >= 0) component_has_actuators_[size_t(c)] = 1;
}

bool Stepper::run(const std::atomic<bool>& stop) {
  start_us_ = monotonic_us();
  start_step_ = sim_.step_count();
  w_ = Window{start_us_, start_step_, io_.dropped()};
  return opt_.lockstep ? run_lockstep(stop) : run_real_time(stop);
}

bool Stepper::done() const { return opt_.duration_s > 0 && sim_.time() >= opt_.duration_s - 1e-9; }

double Stepper::real_time_factor(int64_t now_us) const {
  const int64_t wall = now_us - start_us_;
  return wall > 0 ? double(sim_.step_count() - start_step_) * period_us_ / double(wall) : 0.0;
}

int64_t Stepper::step_timed(int64_t* end_us) {
  const int64_t t0 = monotonic_us();
  sim_.step();
  const int64_t t1 = monotonic_us();
  step_exec_.add(double(t1 - t0));
  run_step_exec_.add(double(t1 - t0));
  time_components(t0);
  if (end_us) *end_us = t1;
  return t1 - t0;
}

int64_t Stepper::publish_timed(int64_t step_us, int64_t late_after_us, int64_t start_us) {
  const int64_t t0 = start_us >= 0 ? start_us : monotonic_us();
  const int64_t t1 = publish(real_time_factor(t0));
  publish_exec_.add(double(t1 - t0));
  stats_.add_cycle(t0, step_us + (t1 - t0), late_after_us > 0 && t1 > late_after_us);
  return t1;
}

bool Stepper::run_lockstep(const std::atomic<bool>& stop) {
  const int64_t timeout_us = std::max<int64_t>(1000, std::llround(opt_.lockstep_timeout_s * 1e6));
  publish(real_time_factor());
  while (!stop && !done()) {
    io_.expect_step(sim_.step_count());  // before a pause too: the answer to this state is kept while paused
    serve_requests();
    if (holding()) {
      if (!wait_paused()) return false;
      continue;
    }
    const int64_t waited_from = monotonic_us();
    int64_t published = waited_from;
    bool said = false;
    for (bool first = true; !io_.has_command() && !io_.has_request(); first = false) {
      if (stop) return true;
      const int64_t now = first ? waited_from : monotonic_us();
      if (now - published >= timeout_us) {
        publish(real_time_factor());
        published = now;
        stats_.add_missed(1);
        if (!said)
          spdlog::info("lockstep: waiting for the hardware/command of step {} (session {}); hardware/state is "
                       "republished every {:g} s, sim time stands still",
                       sim_.step_count(), io_.session(), opt_.lockstep_timeout_s);
        said = true;
      }
      tick_statistics(now);
      if (!io_.poll_until(std::min({published + timeout_us, now + kMaxWaitSliceUs, w_.start_us + kStatsPeriodUs}),
                          true, true))
        return false;
    }
    if (!io_.has_command()) continue;  // a request first: it may pause or reset
    if (said) spdlog::info("lockstep: command for step {} arrived; stepping", sim_.step_count());
    io_.take_command();
    int64_t stepped = 0;
    const int64_t step_us = step_timed(&stepped);
    const int64_t published_at = publish_timed(step_us, 0, stepped);
    after_step();
    tick_statistics(published_at);
  }
  return true;
}

void Stepper::watchdog(int64_t now) {
  const int64_t last = std::max(io_.last_command_us(), resumed_us_);
  const bool lost = last >= 0 && double(now - last) > opt_.watchdog_s * 1e6;
  if (lost == watchdog_holding_) return;
  watchdog_holding_ = lost;
  sim_.hardware().set_hold_all(lost);
  if (lost)
    spdlog::warn("no hardware/command for {:g} ms (watchdog): every actuator holds at step {}", opt_.watchdog_s * 1e3,
                 sim_.step_count());
  else
    spdlog::info("hardware/command is back at step {}: commands apply again", sim_.step_count());
}

bool Stepper::sleep_until(int64_t until_us, int64_t answer_to, const std::atomic<bool>& stop) {
  const int64_t wake = answer_to >= 0 ? until_us : until_us - opt_.spin_us;
  int64_t now = monotonic_us();
  auto answered = [&] { return answer_to >= 0 && io_.answered(answer_to); };
  do {  // at least one pass, so messages are handled even while catching up (without waiting when answered)
    if (stop) return true;
    tick_statistics(now);
    const int64_t until = answered() ? now : std::min({wake, now + kMaxWaitSliceUs, w_.start_us + kStatsPeriodUs});
    if (!io_.poll_until(until, answer_to >= 0, false, answer_to)) return false;
    now = monotonic_us();
  } while (now < wake && !answered());
  while (answer_to < 0 && now < until_us && !stop) {  // --spin-us: the tail without sleeping, still taking messages
    if (!io_.poll_until(now, false, false, -1)) return false;
    now = monotonic_us();
  }
  return true;
}

bool Stepper::run_real_time(const std::atomic<bool>& stop) {
  base_us_ = start_us_;
  base_step_ = sim_.step_count();
  stats_.set_nominal_period_us(period_us_);
  publish(1.0);
  while (!stop && !done()) {
    serve_requests();
    if (holding()) {
      if (!wait_paused()) return false;
      continue;
    }
    auto due = [&] { return base_us_ + std::llround(double(sim_.step_count() + 1 - base_step_) * period_us_); };
    int64_t deadline = due();  // when the state of the step taken next is published
    const bool awaited = opt_.answer_wait_us > 0 && !watchdog_holding_ && io_.last_command_us() >= 0;
    // Catch-up: the step is taken as soon as the controller's answer to the last state published (this step's) is
    // here, at most answer_wait_us after its deadline, and its state waits for the deadline. Skip: the step is taken
    // when due, so that a stall cannot overtake a state computed ahead and publish it next to the newest.
    const bool ahead = awaited && opt_.overrun == Overrun::CatchUp;
    if (!(ahead ? sleep_until(std::max(deadline, monotonic_us()) + opt_.answer_wait_us, sim_.step_count(), stop)
                : sleep_until(deadline, -1, stop)))
      return false;
    if (stop) return true;
    const int64_t now = monotonic_us();
    const int64_t late = now - deadline;
    bool answered = false, skipped = false;
    if (late > std::max<int64_t>(kMaxCatchUpUs, std::llround(10 * period_us_))) {
      stats_.add_missed(std::llround(double(late) / period_us_));
      rebase(now);
    } else if (opt_.overrun == Overrun::Skip && late >= period_us_) {
      answered = io_.take_command();  // the newest command holds through the skipped steps
      stats_.add_missed(skip_to(now));
      deadline = due();
      skipped = true;  // the newest state was not published: nothing answers it
    }
    if (awaited && !ahead && !skipped && !sleep_until(now + opt_.answer_wait_us, sim_.step_count(), stop)) return false;
    answered = io_.take_command() || answered;
    if (!answered && io_.last_command_us() >= 0) stats_.add_missed(1);  // the controller did not answer in time
    watchdog(now);
    const int64_t step_us = step_timed();
    // Catch-up: held until its deadline, so the physics time and the wait for the answer do not move it (a step
    // taken when due or late is published at once).
    if (!sleep_until(deadline, -1, stop)) return false;
    publish_timed(step_us, deadline + std::llround(period_us_));
    after_step();
    tick_statistics(monotonic_us());
  }
  return true;
}

int64_t Stepper::skip_to(int64_t now) {
  int64_t skipped = 0;
  // The last step of a --duration or of a STEP request is always published.
  auto last_left = [&] {
    return steps_left_ == 1 ||
           (opt_.duration_s > 0 && sim_.time() + sim_.control_period() >= opt_.duration_s - 1e-9);
  };
  while (!holding() && !last_left() &&
         base_us_ + std::llround(double(sim_.step_count() + 2 - base_step_) * period_us_) <= now) {
    sim_.step();
    after_step();
    ++skipped;
  }
  return skipped;
}

void Stepper::rebase(int64_t now) {
  base_us_ = now;
  base_step_ = sim_.step_count();
}

int64_t Stepper::publish(double real_time_factor, bool clock_again) {
  io_.publish_state(real_time_factor, clock_again);
  last_publish_us_ = monotonic_us();
  return last_publish_us_;
}

bool Stepper::wait_paused() {
  const int64_t now = monotonic_us();
  if (now - last_publish_us_ >= kPausedRepublishUs) publish(real_time_factor(), true);
  tick_statistics(now);
  return io_.poll_until(std::min({last_publish_us_ + kPausedRepublishUs, now + kMaxWaitSliceUs,
                                  w_.start_us + kStatsPeriodUs}),
                        false, true);
}

std::string Stepper::where() const { return fmt::format("step {} (t={:.3f} s)", sim_.step_count(), sim_.time()); }

sim_response_t Stepper::response_to(const sim_request_t& req, bool ok, std::string message) const {
  sim_response_t a{};
  a.utime = sim_.time_us();
  a.request_id = req.request_id;
  a.op = req.op;
  a.ok = ok;
  a.message = std::move(message);
  a.paused = paused_;
  a.lockstep = opt_.lockstep;
  a.step = sim_.step_count();
  a.period_us = int32_t(std::llround(period_us_));
  a.resets = resets_;
  return a;
}

void Stepper::serve_requests() {
  while (io_.has_request()) serve(io_.take_request());
}

void Stepper::finish_step_request(const std::string& how) {
  if (step_request_.request_id == 0) return;
  spdlog::info("{}", how);
  io_.answer(response_to(step_request_, true, how));
  step_request_ = sim_request_t{};
  step_request_.request_id = 0;
}

void Stepper::after_step() {
  if (steps_left_ == 0 || --steps_left_ > 0) return;
  finish_step_request(fmt::format("stepped {} control step{}: paused at {}", step_request_.steps,
                                  step_request_.steps == 1 ? "" : "s", where()));
}

void Stepper::serve(const sim_request_t& req) {
  const std::string who = req.client.empty() ? "" : fmt::format(" (from {})", clip(req.client));
  auto reply = [&](bool ok, std::string message) {
    if (ok && req.op != sim_request_t::STATUS) request_log_.info(message + who);
    io_.answer(response_to(req, ok, std::move(message)));
  };
  const int64_t now = monotonic_us();
  switch (req.op) {
    case sim_request_t::STATUS:
      return reply(true, fmt::format("{} at {}, {}{}", paused_ ? "paused" : "running", where(),
                                     opt_.lockstep ? "lockstep" : "real time",
                                     resets_ ? fmt::format(", {} reset{}", resets_, resets_ == 1 ? "" : "s") : ""));
    case sim_request_t::PAUSE:
      if (holding()) return reply(true, "already paused at " + where());
      finish_step_request(fmt::format("the step was cut short by a pause after {} of {} steps: paused at {}",
                                      step_request_.steps - steps_left_, step_request_.steps, where()));
      paused_ = true;
      steps_left_ = 0;
      return reply(true, "paused at " + where() + ": sim time holds; `cmctl resume` or `cmctl step N` go on");
    case sim_request_t::RESUME:
      if (!paused_) return reply(true, "already running at " + where());
      finish_step_request("the step was cut short by a resume at " + where());
      paused_ = false;
      steps_left_ = 0;
      rebase(now);
      resumed_us_ = now;
      return reply(true, "resumed at " + where());
    case sim_request_t::STEP:
      if (!paused_)
        return reply(false, fmt::format("cannot step {}: the simulation is running at {}; pause it first (cmctl pause)",
                                        req.steps, where()));
      if (req.steps < 1) return reply(false, fmt::format("cannot step {}: give a number of steps >= 1", req.steps));
      if (steps_left_ > 0)
        return reply(false, fmt::format("cannot step {}: a step of {} is under way ({} left)", req.steps,
                                        step_request_.steps, steps_left_));
      steps_left_ = req.steps;
      step_request_ = req;
      rebase(now);
      resumed_us_ = now;
      return;  // answered by after_step() when the steps are done
    case sim_request_t::RESET: {
      InitialPositions changes;
      const int n = std::min<int>(req.num_joints, int(std::min(req.joint.size(), req.position.size())));
      for (int k = 0; k < n; ++k) changes[req.joint[k]] = req.position[k];
      const int64_t previous = sim_.step_count();
      std::vector<std::string> clamped;
      try {
        clamped = sim_.reset(changes);
      } catch (const ModelError& e) {
        return reply(false, fmt::format("cannot reset: {}; nothing was changed", e.what()));
      }
      finish_step_request("the step was cut short by a reset");
      steps_left_ = 0;
      ++resets_;
      io_.after_reset(previous);
      start_step_ -= previous;  // the real-time factors keep counting the steps taken before
      w_.start_step -= previous;
      rebase(now);
      resumed_us_ = now;
      watchdog_holding_ = sim_.hardware().hold_all();
      publish(real_time_factor());
      std::string pose;
      for (const auto& [joint, q] : sim_.initial_positions()) pose += fmt::format("{}{}={:g}", pose.empty() ? "" : " ", joint, q);
      std::string msg = fmt::format("reset at step {} (t={:.3f} s) to step 0: every joint at its start pose ({}){}",
                                    previous, double(previous) * sim_.control_period(),
                                    pose.empty() ? "0, or the nearest limit" : pose + ", the others at 0 or the nearest limit",
                                    paused_ ? "; still paused" : "");
      for (const std::string& c : clamped) msg += "; " + c;
      return reply(true, msg);
    }
    case sim_request_t::FAIL_COMPONENT: {
      if (const std::string why = sim_.components().fail(req.component, req.reason, sim_.gpio()); !why.empty())
        return reply(false, "cannot fail a hardware component: " + why);
      return reply(true, fmt::format("hardware component '{}' fails at {} (test hook){}; hardware/state reports it "
                                     "and its joints hold until the controller manager sets it not active",
                                     req.component, where(), req.reason.empty() ? "" : ": " + clip(req.reason)));
    }
    case sim_request_t::CONFIG: {
      if (!publish_config_) return reply(false, "this sim_server does not publish its configuration");
      auto [ok, message] = publish_config_();
      return reply(ok, std::move(message));
    }
    case sim_request_t::APPLY_WRENCH: {
      const Eigen::Vector3d f(req.force.x, req.force.y, req.force.z), t(req.torque.x, req.torque.y, req.torque.z);
      if (const std::string why = sim_.apply_wrench(req.link, f, t, req.duration); !why.empty())
        return reply(false, "cannot apply a wrench: " + why);
      if (req.duration == 0) return reply(true, fmt::format("cleared the wrench on '{}' at {}", req.link, where()));
      return reply(true, fmt::format("applying force ({:g}, {:g}, {:g}) N and torque ({:g}, {:g}, {:g}) N*m (world "
                                     "frame) at the centre of mass of '{}' from {} {}",
                                     f.x(), f.y(), f.z(), t.x(), t.y(), t.z(), req.link, where(),
                                     req.duration < 0 ? std::string("until cleared")
                                                      : fmt::format("for {:g} s of sim time", req.duration)));
    }
    default:
      return reply(false, fmt::format("unknown op {} (sim_request_t: STATUS 0, PAUSE 1, RESUME 2, STEP 3, RESET 4, "
                                      "FAIL_COMPONENT 5, APPLY_WRENCH 6, CONFIG 7)",
                                      int(req.op)));
  }
}

void Stepper::time_components(int64_t step_start_us) {
  if (sim_.backend() != Backend::Bullet) return;
  const std::vector<int>& of = sim_.components().component_of();
  for (size_t a = 0; a < of.size(); ++a)
    if (of[a] >= 0) component_ns_[size_t(of[a])] += sim_.actuators().take_work_ns(int(a));
  for (size_t c = 0; c < component_ns_.size(); ++c) {
    if (!component_has_actuators_[c]) continue;
    component_exec_[c].add(double(std::exchange(component_ns_[c], 0)) * 1e-3);
    if (last_step_start_us_ >= 0) component_period_[c].add(double(step_start_us - last_step_start_us_));
  }
  last_step_start_us_ = step_start_us;
}

void Stepper::tick_statistics(int64_t now) {
  if (now - w_.start_us < kStatsPeriodUs) return;
  loop_stats_t s{};
  s.utime = sim_.time_us();
  s.process = "sim_server";
  const int64_t dropped = io_.dropped();
  if (const std::string note = io_.bus().hardware_loss_note(); !note.empty()) spdlog::warn("{}", note);
  stats_.add_dropped(dropped - w_.dropped_before);
  stats_.set_real_time_factor(double(sim_.step_count() - w_.start_step) * period_us_ / double(now - w_.start_us));
  stats_.fill_and_reset(s);
  add_item(s, "step", "stage", step_exec_, nullptr);
  add_item(s, "publish", "stage", publish_exec_, nullptr);
  for (size_t c = 0; c < component_exec_.size(); ++c)
    if (component_has_actuators_[c])
      add_item(s, sim_.components().components()[c].name, "component", component_exec_[c], &component_period_[c]);
  io_.publish_statistics(s);
  w_ = Window{now, sim_.step_count(), dropped};
}

}  // namespace lcm_control::sim
