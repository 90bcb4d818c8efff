#include "test/controller_manager/fake_hardware.hpp"

#include <chrono>
#include <cmath>
#include <random>
#include <stdexcept>

#include "bus/bus.hpp"

namespace lcm_control::testing {

std::vector<FakeActuator> actuators_for(const RobotModel& model) {
  std::vector<FakeActuator> out;
  for (const auto& t : model.transmissions) {
    FakeActuator a;
    a.name = t.actuator;
    switch (t.interfaces.front()) {
      case Interface::Position:
        a.mode = hardware_command_t::MODE_POSITION;
        break;
      case Interface::Velocity:
        a.mode = hardware_command_t::MODE_VELOCITY;
        break;
      case Interface::Effort:
        a.mode = hardware_command_t::MODE_EFFORT;
        break;
    }
    out.push_back(a);
  }
  return out;
}

FakeActuator& find_actuator(std::vector<FakeActuator>& actuators, const std::string& name) {
  for (auto& a : actuators)
    if (a.name == name) return a;
  throw std::runtime_error("no actuator " + name);
}

int simulate(std::vector<FakeActuator>& act, const hardware_command_t* cmd, double dt) {
  int dropped = 0;
  for (size_t k = 0; k < act.size(); ++k) {
    FakeActuator& a = act[k];
    int8_t mode = cmd ? cmd->mode[k] : hardware_command_t::MODE_NONE;
    const double u = cmd ? cmd->command[k] : 0.0;
    if (mode != hardware_command_t::MODE_NONE && mode != a.mode) {
      ++dropped;
      mode = hardware_command_t::MODE_NONE;
    }
    const bool none = mode == hardware_command_t::MODE_NONE;
    switch (a.mode) {
      case hardware_command_t::MODE_POSITION: {
        const double next = none ? a.position : u;
        a.velocity = (next - a.position) / dt;
        a.position = next;
        a.effort = 0;
        break;
      }
      case hardware_command_t::MODE_VELOCITY:
        a.velocity = none ? 0.0 : u;
        a.position += a.velocity * dt;
        a.effort = 0;
        break;
      default: {
        a.effort = none ? 0.0 : u;
        const double acc = (a.effort - a.gravity * std::sin(a.position) - a.damping * a.velocity) / a.inertia;
        a.velocity += acc * dt;
        a.position += a.velocity * dt;
      }
    }
  }
  return dropped;
}

void fill_state(hardware_state_t& s, const std::vector<FakeActuator>& act, int64_t step, int64_t session, int period_us,
                bool lockstep) {
  s.utime = step * period_us;
  s.step = step;
  s.session = session;
  s.lockstep = lockstep;
  s.period_us = period_us;
  s.e_stop = false;
  s.real_time_factor = 1.0;
  s.num_actuators = static_cast<int32_t>(act.size());
  s.num_sensor_values = static_cast<int32_t>(s.sensor_value.size());  // a test's sensor values stay
  s.name.resize(act.size());
  s.mode.resize(act.size());
  s.position.resize(act.size());
  s.velocity.resize(act.size());
  s.effort.resize(act.size());
  for (size_t k = 0; k < act.size(); ++k) {
    s.name[k] = act[k].name;
    s.mode[k] = act[k].mode;
    s.position[k] = act[k].position;
    s.velocity[k] = act[k].velocity;
    s.effort[k] = act[k].effort;
  }
}

namespace {
int64_t random_session() {
  std::random_device rd;
  return (static_cast<int64_t>(rd()) << 20) ^ rd();
}
}  // namespace

FakeHardware::FakeHardware(const std::string& url, std::vector<FakeActuator> actuators, FakeHardwareOptions options)
    : lcm_(url), options_(std::move(options)), act_(std::move(actuators)), session_(random_session()) {
  std::string prefix = options_.ns.empty() ? "" : options_.ns + "/";
  lcm_.subscribe(prefix + "hardware/command", &FakeHardware::on_command, this)->setQueueCapacity(0);
}

FakeHardware::~FakeHardware() { stop(); }

void FakeHardware::start() {
  if (running_) return;
  running_ = true;
  thread_ = std::thread([this] { run(); });
}

void FakeHardware::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

void FakeHardware::pause(bool p) { paused_ = p; }
void FakeHardware::restart_session() { restart_ = true; }

int64_t FakeHardware::step() {
  std::lock_guard<std::mutex> l(mutex_);
  return step_;
}
std::vector<FakeActuator> FakeHardware::actuators() {
  std::lock_guard<std::mutex> l(mutex_);
  return act_;
}
FakeActuator FakeHardware::actuator(const std::string& name) {
  std::lock_guard<std::mutex> l(mutex_);
  for (const auto& a : act_)
    if (a.name == name) return a;
  return {};
}
void FakeHardware::set_position(const std::string& name, double position) {
  std::lock_guard<std::mutex> l(mutex_);
  for (auto& a : act_)
    if (a.name == name) a.position = position, a.velocity = 0;
}
std::vector<FakeHardware::Record> FakeHardware::records() {
  std::lock_guard<std::mutex> l(mutex_);
  return records_;
}
int64_t FakeHardware::dropped() {
  std::lock_guard<std::mutex> l(mutex_);
  return dropped_;
}

bool FakeHardware::run_steps(int64_t n, double timeout_s) {
  const int64_t target = step() + n;
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (step() < target) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return true;
}

void FakeHardware::on_command(const lcm::ReceiveBuffer*, const std::string&, const hardware_command_t* m) {
  std::lock_guard<std::mutex> l(mutex_);
  if (m->session != session_ || m->num_actuators != static_cast<int32_t>(act_.size())) {
    ++dropped_;
    return;
  }
  if (options_.lockstep && m->step != step_) return;  // not the step we wait for
  last_ = *m;
  have_command_ = true;
}

void FakeHardware::publish_state() {
  hardware_state_t s{};
  {
    std::lock_guard<std::mutex> l(mutex_);
    fill_state(s, act_, step_, session_, options_.period_us, options_.lockstep);
  }
  lcm_.publish(options_.ns.empty() ? "hardware/state" : options_.ns + "/hardware/state", &s);
}

void FakeHardware::record(const hardware_command_t* c) {
  Record r;
  r.step = step_;
  if (c) {
    r.mode = c->mode;
    r.command = c->command;
  } else {
    r.mode.assign(act_.size(), hardware_command_t::MODE_NONE);
    r.command.assign(act_.size(), 0.0);
  }
  for (const auto& a : act_) r.position.push_back(a.position);
  records_.push_back(std::move(r));
}

void FakeHardware::run() {
  const double dt = options_.period_us * 1e-6;
  auto next = std::chrono::steady_clock::now();
  while (running_) {
    if (restart_.exchange(false)) {
      std::lock_guard<std::mutex> l(mutex_);
      session_ = random_session();
      step_ = 0;
      have_command_ = false;
    }
    if (paused_) {
      lcm_.handleTimeout(5);
      next = std::chrono::steady_clock::now();
      continue;
    }
    if (options_.lockstep) {
      {
        std::lock_guard<std::mutex> l(mutex_);
        have_command_ = false;
      }
      publish_state();
      auto last_pub = std::chrono::steady_clock::now();
      bool got = false;
      while (running_ && !paused_ && !restart_) {
        lcm_.handleTimeout(5);
        {
          std::lock_guard<std::mutex> l(mutex_);
          got = have_command_;
        }
        if (got) break;
        if (std::chrono::steady_clock::now() - last_pub > std::chrono::duration<double>(options_.republish_s)) {
          publish_state();
          last_pub = std::chrono::steady_clock::now();
        }
      }
      if (!got) continue;
      std::lock_guard<std::mutex> l(mutex_);
      dropped_ += simulate(act_, &last_, dt);
      record(&last_);
      ++step_;
    } else {
      next += std::chrono::microseconds(options_.period_us);
      while (lcm_.handleTimeout(0) > 0) {
      }
      {
        std::lock_guard<std::mutex> l(mutex_);
        dropped_ += simulate(act_, have_command_ ? &last_ : nullptr, dt);
        record(have_command_ ? &last_ : nullptr);
        ++step_;
      }
      publish_state();
      std::this_thread::sleep_until(next);
    }
  }
}

}  // namespace lcm_control::testing
