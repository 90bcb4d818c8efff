// An is_async controller's own thread (ROS 2's AsyncFunctionHandler). The controller reads and writes a copy of the
// hardware of its own (its shadow, given to its init()); the loop hands it a job, the state copied in and the calls
// it owes (starting, stopping, restart) then an update, and takes the commands back in the first cycle after it
// finished. While a job runs the loop neither waits for it nor hands it another: a due update is skipped (counted).
// The hand-over is an atomic flag (release/acquire) and one eventfd write; nothing in it allocates or locks.
// In lockstep the job runs in the loop's thread, in the cycle it is due, so that runs repeat bit for bit.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <thread>
#include <vector>

#include "controller_interface/controller.hpp"
#include "controller_manager/hardware.hpp"

namespace lcm_control::cm {

class AsyncUpdate {
 public:
  enum class Call : uint8_t { Start, Stop, Restart };

  // `shadow` is the Hardware the controller was initialised on; both outlive this.
  AsyncUpdate(Controller& controller, Hardware& shadow);
  ~AsyncUpdate();  // waits for the job running, makes the calls still owed, stops the thread
  AsyncUpdate(const AsyncUpdate&) = delete;
  AsyncUpdate& operator=(const AsyncUpdate&) = delete;

  bool busy() const { return busy_.load(std::memory_order_acquire); }
  // A call to make before its next update (a Start then a Stop cancel each other).
  void owe(Call call);
  bool owes() const { return owed_n_ > 0; }

  // Only when !busy(): copies `hw`'s state (and, before a Start, the commands the loop set on `claimed` joints and
  // gpios) into the shadow, then makes the owed calls and, with `update`, update(now, period): on the thread, or in
  // the caller's with `here`.
  void run(const Hardware& hw, const std::vector<JointData*>& claimed, const std::vector<GpioData*>& gpios,
           const Time& now, double period, bool update, bool here);
  // Only when !busy(): whether a job finished since the last take(); then `updated` says whether one made an update,
  // and the commands it wrote on `claimed` / `gpios` (joints still owned by it) are copied into `hw`.
  bool take(Hardware& hw, const std::vector<JointData*>& claimed, const std::vector<GpioData*>& gpios, bool* updated,
            double* exec_us);

  int64_t skipped() const { return skipped_; }
  void count_skipped() { ++skipped_; }

 private:
  void work();
  void job();

  Controller& controller_;
  Hardware& shadow_;
  std::array<Call, 4> owed_{};
  size_t owed_n_ = 0;
  // The job, written by the loop before busy_ is set and read by the thread after it.
  std::array<Call, 4> calls_{};
  size_t calls_n_ = 0;
  Time now_;
  double period_ = 0;
  bool update_ = false;
  // Its outcome, written by the thread before busy_ is cleared.
  bool done_ = false, updated_ = false;
  double exec_us_ = 0;
  int64_t skipped_ = 0;
  std::atomic<bool> busy_{false};
  std::atomic<bool> quit_{false};
  int wake_fd_ = -1;
  std::thread thread_;
};

}  // namespace lcm_control::cm
