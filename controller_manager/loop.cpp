#include "controller_manager/loop.hpp"

#include <algorithm>
#include <utility>

#include "bus/bus.hpp"

namespace lcm_control::cm {

// A joint a controller takes over on the same interface from one stopped in the same switch keeps that controller's
// last command (bumpless); any other joint (a <ros2_control> joint whose interface changes too: a velocity is no
// position) is first commanded to hold where it is, so that the command written in this cycle, before the new
// controller's first update, is never a stale or zero value.
bool Loop::handed_over(const JointData* j, Interface interface) const {
  for (const ControllerSlot* s : pending_stop_)
    for (size_t k = 0; k < s->claimed.size(); ++k)
      if (s->claimed[k] == j) return s->controller->claim().interface_of(k) == interface;
  return false;
}

namespace {
bool has(const std::vector<int>& v, int k) { return std::find(v.begin(), v.end(), k) != v.end(); }
}  // namespace

bool may_run(const Controller& c, const std::vector<ComponentData>& components) {
  for (int k : c.uses().commands)
    if (!components[size_t(k)].commandable()) return false;
  for (int k : c.uses().reads)
    if (!components[size_t(k)].readable()) return false;
  return true;
}

bool affected_by(const Controller& c, int component, Lifecycle state) {
  return (has(c.uses().commands, component) && !ComponentData::commandable(state)) ||
         (has(c.uses().reads, component) && !ComponentData::readable(state));
}

void Loop::fail_components(const hardware_state_t& st) {
  for (int e = 0; e < st.num_component_errors; ++e) {
    const int k = hw_.component_index(st.error_component[size_t(e)]);
    if (k < 0) continue;
    ComponentData& c = hw_.components()[size_t(k)];
    if (!c.readable()) continue;  // unconfigured or finalized already: the error is acknowledged
    c.state = Lifecycle::Unconfigured;
    c.error_fresh = true;
    c.error_step = st.step;
    for (auto& s : slots_)
      if (s->running && affected_by(*s->controller, k, Lifecycle::Unconfigured)) {
        stop(*s);
        s->stopped_by_error = true;
        stop_writers_of(*s, *s);
      }
    chain_modes();
  }
}

bool Loop::claims_free(const ControllerSlot& s) const {
  for (const JointData* j : s.claimed)
    if (j->owner) return false;
  for (const GpioData* g : s.claimed_gpios)
    if (g->owner) return false;
  return true;
}

void Loop::fail_controller(ControllerSlot& s) {
  s.failure = std::exchange(s.controller->failure_, nullptr);
  s.failure_step = step_;
  stop(s);
  stop_writers_of(s, s);
  chain_modes();
  for (size_t f = 0; f < s.fallbacks.size(); ++f) {
    s.fallback_started[f] = 0;
    for (auto& other : slots_)
      if (other->name == s.fallbacks[f] && !other->running && may_run(*other->controller, hw_.components()) &&
          claims_free(*other)) {
        start(*other);
        s.fallback_started[f] = 1;
      }
  }
}

void Loop::stop_writers_of(const ControllerSlot& s, const ControllerSlot& cause) {
  for (auto& w : slots_) {
    if (!w->running) continue;
    bool writes = false;
    for (const JointData* j : w->claimed) writes = writes || j->exported_by == s.name;
    if (!writes) continue;
    stop(*w);
    w->chain_stopped_by = &cause;
    stop_writers_of(*w, cause);
  }
}

void Loop::start(ControllerSlot& s) {
  for (size_t k = 0; k < s.claimed.size(); ++k) {
    JointData* j = s.claimed[k];
    const Interface interface = s.controller->claim().interface_of(k);
    if (!handed_over(j, interface)) {
      j->command = interface == Interface::Position ? j->position : 0.0;
      j->damping = 0;
    }
    j->owner = s.controller.get();
    j->owned_as = interface;
    j->soft_position.reset();
  }
  for (GpioData* g : s.claimed_gpios) g->owner = s.controller.get();
  s.first_step = s.last_update_utime = s.last_update_mono = -1;
  if (s.async) {
    call_async(s, AsyncUpdate::Call::Start);
  } else {
    s.controller->running_ = true;
    s.controller->starting(now_);
  }
  s.running = true;
  s.ever_started = true;
}

void Loop::stop(ControllerSlot& s) {
  if (s.async) {
    call_async(s, AsyncUpdate::Call::Stop);
  } else {
    s.controller->stopping(now_);
    s.controller->running_ = false;
  }
  s.running = false;
  for (JointData* j : s.claimed)
    if (j->owner == s.controller.get()) j->owner = nullptr;
  for (GpioData* g : s.claimed_gpios)
    if (g->owner == s.controller.get()) g->owner = nullptr;
}

Loop::Outcome Loop::cycle(const hardware_state_t& st, hardware_command_t& cmd) {
  const int64_t t0 = monotonic_us();
  bool restart = restart_;
  if (!have_state_ || st.session != session_) {
    restart = true;
  } else if (st.step == step_) {
    if (!pending_) return Outcome::Repeated;
    apply_switch();  // a paused hardware repeats its step: switching must not wait for an update
    last_switch_step_ = step_;
    // The controllers it started answer this step too, as if started before it came (so the step a lockstep run
    // starts its controllers at does not depend on whether the first state or the spawner came first).
    const double nominal = st.period_us * 1e-6;
    int64_t mark = -1;
    for (ControllerSlot* s : order_)
      if (s->running && s->last_update_utime < 0) {
        update(*s, st, nominal, mark);
        hw_.enforce_soft_limits(nominal, s->controller.get());
      }
    hw_.write(st, cmd);
    return Outcome::Answered;
  } else if (st.step < step_ || st.utime < now_.utime) {
    restart = true;
  } else if (e_stop_ && !st.e_stop) {
    restart = true;
  } else if (st.step > step_ + 1) {
    stats_.add_missed(st.step - step_ - 1);
  }
  const double period = restart ? st.period_us * 1e-6 : static_cast<double>(st.utime - now_.utime) * 1e-6;
  have_state_ = true;
  restart_ = false;
  session_ = st.session;
  step_ = st.step;
  e_stop_ = st.e_stop;
  now_.utime = st.utime;

  hw_.read(st);
  if (st.num_component_errors > 0) fail_components(st);
  if (restart) {
    ++restarts_;
    hw_.reset_soft_limits();
    for (auto& s : slots_) {
      s->first_step = s->last_update_utime = s->last_update_mono = -1;
      if (s->running && s->async) call_async(*s, AsyncUpdate::Call::Restart);
      else if (s->running) s->controller->restart(now_);
    }
  }
  if (before_update_) before_update_->before_update(now_);
  int64_t mark = -1;  // one clock read between two updates times both
  for (ControllerSlot* s : order_) update(*s, st, period, mark);
  if (pending_) {
    apply_switch();
    last_switch_step_ = step_;
  }
  hw_.enforce_soft_limits(period);
  hw_.write(st, cmd);
  stats_.set_real_time_factor(st.real_time_factor);
  stats_.set_nominal_period_us(st.lockstep ? 0.0 : static_cast<double>(st.period_us));
  const int64_t t1 = monotonic_us();
  stats_.add_cycle(t0, t1 - t0, st.period_us > 0 && t1 - t0 > st.period_us);
  return Outcome::Answered;
}

void Loop::update(ControllerSlot& s, const hardware_state_t& st, double period, int64_t& mark) {
  double own_period = period;
  if (s.async) {
    const bool is_due = s.running && due(s, st, period, &own_period);
    update_async(s, is_due, own_period, st.lockstep);
    return;
  }
  if (!s.running || !due(s, st, period, &own_period)) return;
  s.last_update_utime = now_.utime;
  if (mark < 0) mark = monotonic_us();
  if (s.last_update_mono >= 0) s.period.add(static_cast<double>(mark - s.last_update_mono));
  s.last_update_mono = mark;
  s.controller->update(now_, own_period);
  if (s.controller->failure_) fail_controller(s);
  const int64_t done = monotonic_us();
  s.exec.add(static_cast<double>(done - mark));
  mark = done;
}

bool Loop::due(ControllerSlot& s, const hardware_state_t& st, double period, double* own_period) {
  if (s.update_rate_hz <= 0 || st.period_us <= 0) return true;
  const int64_t every = std::max<int64_t>(1, std::llround(1e6 / (s.update_rate_hz * double(st.period_us))));
  if (s.first_step < 0) s.first_step = step_;
  if ((step_ - s.first_step) % every != 0) return false;
  *own_period = s.last_update_utime < 0 ? double(every) * period
                                        : static_cast<double>(now_.utime - s.last_update_utime) * 1e-6;
  return true;
}

void Loop::take_async(ControllerSlot& s) {
  bool updated = false;
  double exec_us = 0;
  if (!s.async->take(hw_, s.claimed, s.claimed_gpios, &updated, &exec_us)) return;
  if (updated) s.exec.add(exec_us);
  if (s.controller->failure_) {
    if (s.running)
      fail_controller(s);
    else
      s.controller->failure_ = nullptr;
  }
}

void Loop::call_async(ControllerSlot& s, AsyncUpdate::Call call) {
  s.async->owe(call);
  if (!s.async->busy()) s.async->run(hw_, s.claimed, s.claimed_gpios, now_, 0, false, true);
}

void Loop::update_async(ControllerSlot& s, bool due, double own_period, bool here) {
  AsyncUpdate& a = *s.async;
  if (a.busy()) {
    if (due) a.count_skipped();
    return;
  }
  take_async(s);
  due = due && s.running;  // not if it failed just now
  if (!due && !a.owes()) return;
  if (!here && s.endpoints && s.endpoints->held() > 0) {  // its commands first (between cycles), then its update
    if (due) a.count_skipped();
    return;
  }
  if (due) {
    s.last_update_utime = now_.utime;
    const int64_t mark = monotonic_us();
    if (s.last_update_mono >= 0) s.period.add(static_cast<double>(mark - s.last_update_mono));
    s.last_update_mono = mark;
  }
  here = here || !due;  // only calls owed: made here, as call_async() does
  a.run(hw_, s.claimed, s.claimed_gpios, now_, own_period, due, here);
  if (here) take_async(s);
}

void Loop::set_pending_switch(const std::vector<ControllerSlot*>& stop, const std::vector<ControllerSlot*>& start) {
  pending_stop_ = stop;
  pending_start_ = start;
  pending_ = true;
}

void Loop::set_pending_component(int index, Lifecycle state) {
  pending_component_ = index;
  pending_component_state_ = state;
}

void Loop::apply_switch() {
  for (ControllerSlot* s : pending_stop_)
    if (s->running) {
      stop(*s);
      if (pending_component_ >= 0) stop_writers_of(*s, *s);  // a component leaving active takes its chains with it
    }
  if (pending_component_ >= 0) hw_.components()[size_t(pending_component_)].state = pending_component_state_;
  pending_component_ = -1;
  for (ControllerSlot* s : pending_start_) {
    s->start_refused = !may_run(*s->controller, hw_.components());
    if (!s->start_refused) start(*s);
  }
  pending_stop_.clear();  // keeps the capacity
  pending_start_.clear();
  pending_ = false;
  chain_modes();
}

void Loop::apply_now() {
  if (!pending_) return;
  apply_switch();
  last_switch_step_ = -1;
}

void Loop::cancel_pending() {
  pending_component_ = -1;
  pending_stop_.clear();
  pending_start_.clear();
  pending_ = false;
}

void Loop::stop_all() {
  for (auto& s : slots_)
    if (s->running) stop(*s);
  chain_modes();
}

void Loop::reorder() {
  // Kahn's order over "writes a reference interface of": among those ready, load order.
  const size_t n = slots_.size();
  std::vector<std::vector<size_t>> followers(n);
  std::vector<size_t> waiting(n, 0);
  for (size_t a = 0; a < n; ++a)
    for (const JointData* j : slots_[a]->claimed)
      if (!j->exported_by.empty())
        for (size_t b = 0; b < n; ++b)
          if (b != a && slots_[b]->name == j->exported_by) {
            followers[a].push_back(b);
            ++waiting[b];
          }
  order_.clear();
  std::vector<bool> placed(n, false);
  while (order_.size() < n) {
    bool progress = false;
    for (size_t k = 0; k < n; ++k)
      if (!placed[k] && waiting[k] == 0) {
        placed[k] = progress = true;
        order_.push_back(slots_[k].get());
        for (size_t f : followers[k]) --waiting[f];
        break;
      }
    if (!progress)  // a cycle (refused at load): load order for the rest
      for (size_t k = 0; k < n; ++k)
        if (!placed[k]) {
          placed[k] = true;
          order_.push_back(slots_[k].get());
        }
  }
}

void Loop::chain_modes() {
  for (auto& s : slots_) {
    bool chained = false;
    for (const JointData* r : s->controller->exported_) chained = chained || r->owner != nullptr;
    s->controller->chained_ = chained;
  }
}

}  // namespace lcm_control::cm
