#include "rt/outbox.hpp"

#include <poll.h>
#include <pthread.h>
#include <sched.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>

namespace lcm_control {

Outbox::Outbox(Send send, size_t slots, size_t slot_bytes) : slots_(slots), send_(std::move(send)) {
  if (slots == 0) throw std::invalid_argument("Outbox needs at least one slot");
  for (Slot& s : slots_) {
    s.bytes.resize(slot_bytes);
    s.channel.reserve(128);
  }
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (wake_fd_ < 0) throw std::runtime_error("Outbox: eventfd failed");
  thread_ = std::thread([this] { run(); });
}

Outbox::Outbox(lcm::LCM& lc, size_t slots, size_t slot_bytes)
    : Outbox([&lc](const Slot& s) { lc.publish(s.channel, s.bytes.data(), static_cast<unsigned>(s.size)); }, slots,
             slot_bytes) {}

Outbox::~Outbox() {
  stop_.store(true);
  const uint64_t one = 1;
  (void)!write(wake_fd_, &one, sizeof one);
  thread_.join();
  close(wake_fd_);
}

Outbox::Slot* Outbox::begin() {
  if (producing_.test_and_set(std::memory_order_acquire)) {
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return nullptr;
  }
  const uint64_t h = head_.load(std::memory_order_relaxed);
  if (h - tail_.load(std::memory_order_acquire) >= slots_.size()) {
    producing_.clear(std::memory_order_release);
    dropped_.fetch_add(1, std::memory_order_relaxed);
    return nullptr;
  }
  return &slots_[h % slots_.size()];
}

void Outbox::commit() {
  const uint64_t h = head_.load(std::memory_order_relaxed);
  const size_t size = slots_[h % slots_.size()].size;
  if (size > largest_.load(std::memory_order_relaxed)) largest_.store(size, std::memory_order_relaxed);
  head_.store(h + 1);  // seq_cst with sleeping_ below and in run(): one of the two sees the other
  producing_.clear(std::memory_order_release);
  if (sleeping_.load() && !send_here_.load(std::memory_order_relaxed)) {
    const uint64_t one = 1;
    (void)!write(wake_fd_, &one, sizeof one);
  }
}

void Outbox::abandon() { producing_.clear(std::memory_order_release); }

size_t Outbox::send_queued() {
  if (consuming_.test_and_set(std::memory_order_acquire)) return 0;
  const size_t n = send_from_tail();
  consuming_.clear(std::memory_order_release);
  return n;
}

size_t Outbox::send_from_tail() {
  size_t n = 0;
  for (uint64_t t = tail_.load(std::memory_order_relaxed); t < head_.load(std::memory_order_acquire); ++n) {
    Slot& s = slots_[t % slots_.size()];
    send_(s);
    const size_t largest = largest_.load(std::memory_order_relaxed);
    if (s.bytes.size() < largest) s.bytes.resize(largest);  // here, so that the producer need not
    tail_.store(++t, std::memory_order_release);
    sent_.fetch_add(1, std::memory_order_relaxed);
  }
  return n;
}

void Outbox::flush() {
  const uint64_t target = head_.load();
  while (tail_.load(std::memory_order_acquire) < target && thread_.joinable()) {
    if (send_here_.load(std::memory_order_relaxed)) send_queued();
    if (tail_.load(std::memory_order_acquire) < target) std::this_thread::sleep_for(std::chrono::microseconds(50));
  }
}

void Outbox::run() {
  // Not the loop's real-time policy, which a thread inherits from the thread that created it.
  sched_param p{};
  pthread_setschedparam(pthread_self(), SCHED_OTHER, &p);
  pthread_setname_np(pthread_self(), "outbox");
  for (;;) {
    if (!consuming_.test_and_set(std::memory_order_acquire)) {
      send_from_tail();
      consuming_.clear(std::memory_order_release);
    }
    if (stop_.load()) {
      send_queued();  // what came while the caller of send_queued held the turn
      return;
    }
    const uint64_t t = tail_.load(std::memory_order_acquire);
    sleeping_.store(true);
    if ((head_.load() != t && !send_here_.load(std::memory_order_relaxed)) || stop_.load()) {
      sleeping_.store(false);
      continue;
    }
    pollfd fd{wake_fd_, POLLIN, 0};
    poll(&fd, 1, 100);
    uint64_t n = 0;
    (void)!read(wake_fd_, &n, sizeof n);
    sleeping_.store(false);
  }
}

}  // namespace lcm_control
