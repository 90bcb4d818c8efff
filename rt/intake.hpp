// Work a message needs before a loop can take it (decoding, checking, planning), done on a thread of its own, so
// that a large message (a 100,000-point trajectory goal) never stalls a cycle: submit() hands the job over, and the
// loop's thread runs each job's result (what the job returns) at its next drain(), between cycles, in the order the
// jobs were submitted, all of one job's work taken whole; off the loop, the loop's thread never waits for the intake's.
// In place (lockstep, or without a thread), a job and its result run at once in submit(), so that runs repeat bit
// for bit. dispose() lets the thread free what the loop no longer needs (a replaced trajectory).
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <type_traits>

namespace lcm_control {

class Intake {
 public:
  using Result = std::function<void()>;  // runs on the loop's thread
  using Job = std::function<Result()>;   // runs on the intake's thread: must not touch what the loop uses

  Intake();
  ~Intake();  // drops the jobs not yet run and the results not yet taken
  Intake(const Intake&) = delete;
  Intake& operator=(const Intake&) = delete;

  // On: submit() runs the job and its result at once, after the results of the jobs submitted before (waiting for
  // them). Off (the default): the thread runs it.
  void set_in_place(bool on) { in_place_.store(on, std::memory_order_relaxed); }
  bool in_place() const { return in_place_.load(std::memory_order_relaxed); }

  void submit(Job job);
  // What the loop's thread hears of the jobs it submits off the loop (not in place): `submitted` in submit(), and
  // `taken` in the drain() that runs the job's result (or would: a job with none), in the same order. The controller
  // manager stamps an input at the cycle after it was taken (controller_manager/input_stamps.hpp).
  void set_hooks(std::function<void()> submitted, std::function<void()> taken) {
    submitted_ = std::move(submitted);
    taken_ = std::move(taken);
  }
  // The results of the jobs done, in their order; how many ran (with hooks set, one per job, with a result or not).
  // Loop thread only.
  size_t drain();
  // Jobs waiting, running, or whose results wait for drain().
  bool busy() const;
  // Destroys `garbage` (moved in) on the intake's thread, in place or not: freeing has no result to order.
  template <class T>
  void dispose(T&& garbage) {
    // Moved into the job, so the job holds the only reference whenever the thread runs it.
    enqueue([held = std::make_shared<std::decay_t<T>>(std::forward<T>(garbage))]() mutable -> Result {
      held.reset();
      return {};
    });
  }
  int64_t done() const { return done_.load(std::memory_order_relaxed); }  // jobs run on the thread

 private:
  void work();
  // From the loop's thread: never waits for the intake's thread (a nice-19 thread holding the lock while it waits
  // for a CPU would hold the loop too). A job goes to outgoing_ and is handed over whenever the lock is free.
  void enqueue(Job job);
  void hand_over(std::unique_lock<std::mutex>& lock);  // outgoing_ into jobs_, the lock held
  std::deque<Job> outgoing_;                            // the loop's thread only
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<Job> jobs_;
  std::deque<Result> results_;
  size_t running_ = 0;
  bool stop_ = false;
  std::atomic<bool> in_place_{false};
  std::function<void()> submitted_, taken_;  // set_hooks(): the loop's thread only
  std::atomic<int64_t> done_{0};
  std::thread thread_;
};

}  // namespace lcm_control
