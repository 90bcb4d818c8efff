#include "controller_manager/async_update.hpp"

#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <system_error>
#include <utility>

#include "rt/clock.hpp"

namespace lcm_control::cm {

AsyncUpdate::AsyncUpdate(Controller& controller, Hardware& shadow) : controller_(controller), shadow_(shadow) {
  wake_fd_ = eventfd(0, EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::system_error(errno, std::generic_category(), "eventfd for an async controller");
  thread_ = std::thread([this] { work(); });
}

AsyncUpdate::~AsyncUpdate() {
  while (busy()) std::this_thread::yield();
  quit_.store(true, std::memory_order_release);
  const uint64_t one = 1;
  if (write(wake_fd_, &one, sizeof one) < 0) {
  }
  thread_.join();
  close(wake_fd_);
  calls_ = owed_;
  calls_n_ = std::exchange(owed_n_, 0);
  update_ = false;
  job();  // a controller stopped while its update ran gets its stopping() now
}

void AsyncUpdate::owe(Call call) {
  if (owed_n_ > 0) {
    Call& last = owed_[owed_n_ - 1];
    if (last == Call::Start && call == Call::Stop) {  // started and stopped before it ran: neither happened
      --owed_n_;
      return;
    }
    if (last == Call::Start && call == Call::Restart) return;  // a start is from the current state already
    if (last == call) return;
  }
  if (owed_n_ < owed_.size()) owed_[owed_n_++] = call;
}

void AsyncUpdate::run(const Hardware& hw, const std::vector<JointData*>& claimed, const std::vector<GpioData*>& gpios,
                      const Time& now, double period, bool update, bool here) {
  std::vector<JointData>& js = shadow_.joints();
  const std::vector<JointData>& from = hw.joints();
  for (size_t k = 0; k < js.size() && k < from.size(); ++k) {
    js[k].position = from[k].position;
    js[k].velocity = from[k].velocity;
    js[k].effort = from[k].effort;
  }
  const bool starting = std::find(owed_.begin(), owed_.begin() + long(owed_n_), Call::Start) != owed_.begin() + long(owed_n_);
  if (starting) {  // its joints hold as the loop set them until its first update writes them
    for (const JointData* j : claimed) {
      JointData& s = js[size_t(j - from.data())];
      s.command = j->command;
      s.damping = j->damping;
    }
    for (const GpioData* g : gpios) shadow_.gpios()[size_t(g - hw.gpios().data())].command = g->command;
  }
  for (size_t k = 0; k < shadow_.gpios().size() && k < hw.gpios().size(); ++k) shadow_.gpios()[k].state = hw.gpios()[k].state;
  for (size_t k = 0; k < shadow_.sensors().size() && k < hw.sensors().size(); ++k) {
    SensorData& s = shadow_.sensors()[k];
    const SensorData& f = hw.sensors()[k];
    std::copy_n(f.values.begin(), std::min(s.values.size(), f.values.size()), s.values.begin());
    s.present = f.present;
  }
  for (size_t k = 0; k < shadow_.components().size() && k < hw.components().size(); ++k)
    shadow_.components()[k].state = hw.components()[k].state;
  calls_ = owed_;
  calls_n_ = std::exchange(owed_n_, 0);
  now_ = now;
  period_ = period;
  update_ = update;
  if (here) {
    job();
    return;
  }
  busy_.store(true, std::memory_order_release);
  const uint64_t one = 1;
  if (write(wake_fd_, &one, sizeof one) < 0) busy_.store(false, std::memory_order_release);
}

bool AsyncUpdate::take(Hardware& hw, const std::vector<JointData*>& claimed, const std::vector<GpioData*>& gpios,
                       bool* updated, double* exec_us) {
  if (!done_) return false;
  done_ = false;
  *updated = std::exchange(updated_, false);
  *exec_us = exec_us_;
  if (!*updated) return true;
  const std::vector<JointData>& js = shadow_.joints();
  for (JointData* j : claimed) {
    if (j->owner != &controller_) continue;
    const JointData& s = js[size_t(j - hw.joints().data())];
    j->command = s.command;
    j->damping = s.damping;
  }
  for (GpioData* g : gpios)
    if (g->owner == &controller_) g->command = shadow_.gpios()[size_t(g - hw.gpios().data())].command;
  return true;
}

void AsyncUpdate::job() {
  for (size_t k = 0; k < calls_n_; ++k) {
    switch (calls_[k]) {
      case Call::Start:
        controller_.running_ = true;
        controller_.starting(now_);
        break;
      case Call::Stop:
        controller_.stopping(now_);
        controller_.running_ = false;
        break;
      case Call::Restart:
        controller_.restart(now_);
        break;
    }
  }
  if (update_ && controller_.running_) {
    const int64_t t0 = monotonic_us();
    controller_.update(now_, period_);
    exec_us_ = static_cast<double>(monotonic_us() - t0);
    updated_ = true;  // until take(): a job of calls only after it does not hide its commands
  }
  done_ = true;
}

void AsyncUpdate::work() {
  for (;;) {
    uint64_t n = 0;
    if (read(wake_fd_, &n, sizeof n) < 0 && errno == EINTR) continue;
    if (quit_.load(std::memory_order_acquire)) return;
    if (!busy_.load(std::memory_order_acquire)) continue;
    job();
    busy_.store(false, std::memory_order_release);
  }
}

}  // namespace lcm_control::cm
