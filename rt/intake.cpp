#include "rt/intake.hpp"

#include "rt/scheduling.hpp"

namespace lcm_control {

Intake::Intake() : thread_([this] { work(); }) {}

Intake::~Intake() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
    jobs_.clear();
  }
  wake_.notify_one();
  thread_.join();
}

void Intake::enqueue(Job job) {
  outgoing_.push_back(std::move(job));
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (lock) hand_over(lock);
}

void Intake::hand_over(std::unique_lock<std::mutex>& lock) {
  if (outgoing_.empty()) return;
  for (Job& j : outgoing_) jobs_.push_back(std::move(j));
  outgoing_.clear();
  lock.unlock();
  wake_.notify_one();
  lock.lock();
}

void Intake::submit(Job job) {
  if (!in_place()) {
    if (submitted_) submitted_();
    if (!taken_) return enqueue(std::move(job));
    return enqueue([this, job = std::move(job)]() -> Result {
      return [this, r = job()]() {
        if (r) r();
        if (taken_) taken_();
      };
    });
  }
  {  // what was submitted before takes effect first
    std::unique_lock<std::mutex> lock(mutex_);
    hand_over(lock);
    idle_.wait(lock, [&] { return jobs_.empty() && running_ == 0; });
  }
  drain();
  if (Result r = job()) r();
}

size_t Intake::drain() {
  std::deque<Result> ready;
  {
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock) return 0;  // the thread holds it: taken at the next drain, never waited for
    hand_over(lock);
    if (results_.empty()) return 0;
    ready.swap(results_);
  }
  size_t n = 0;
  for (Result& r : ready)
    if (r) {
      r();
      ++n;
    }
  return n;
}

bool Intake::busy() const {
  if (!outgoing_.empty()) return true;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  return !lock || !jobs_.empty() || running_ > 0 || !results_.empty();
}

void Intake::work() {
  become_background_thread("lcm_ctl intake");  // never ahead of the loop for a CPU, whatever the loop's policy
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
    if (stop_) return;
    Job job = std::move(jobs_.front());
    jobs_.pop_front();
    ++running_;
    lock.unlock();
    Result r = job();
    job = nullptr;  // what the job held is freed here, not on the loop
    done_.fetch_add(1, std::memory_order_relaxed);
    lock.lock();
    if (r) results_.push_back(std::move(r));
    --running_;
    if (jobs_.empty() && running_ == 0) idle_.notify_all();
  }
}

}  // namespace lcm_control
