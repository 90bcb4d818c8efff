// Sends encoded messages from a thread of its own, so that a real-time loop hands bytes over and never waits on a
// socket or a lock (ros_controllers' realtime_publisher, as one queue for every publisher of a process). A fixed
// ring of slots whose buffers are kept: begin() and commit() neither allocate (once a slot has carried a message
// as big), lock nor make a system call, except one eventfd write (non-blocking) when the sending thread sleeps.
// A message is dropped, and counted, when the ring is full or another thread is handing one over at that moment.
// Messages leave in the order they were committed.
// In lockstep nothing waits on the loop but its peer, and on one CPU waking the thread for each message costs two
// context switches: there the loop may send what it queued itself (send_here, send_queued), at a point where the peer
// already has what it waits for.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <thread>
#include <vector>

namespace lcm {
class LCM;
}

namespace lcm_control {

class Outbox {
 public:
  struct Slot {
    std::string channel;
    std::vector<uint8_t> bytes;  // size() is the room to encode into; the message is its first `size` bytes
    size_t size = 0;
  };
  using Send = std::function<void(const Slot&)>;

  // `send` runs on the sending thread only.
  explicit Outbox(Send send, size_t slots = 128, size_t slot_bytes = 4096);
  // Publishes on lc (LCM's publish is thread-safe; give the outbox an lcm::LCM of its own to keep its sends off the
  // loop's own publish lock).
  explicit Outbox(lcm::LCM& lc, size_t slots = 128, size_t slot_bytes = 4096);
  ~Outbox();  // sends what was committed, then stops
  Outbox(const Outbox&) = delete;
  Outbox& operator=(const Outbox&) = delete;

  // The slot to fill, or nullptr (counted in dropped()). A non-null begin() must be followed by commit() or
  // abandon() on the same thread before the next begin().
  Slot* begin();
  void commit();
  void abandon();

  // On: commit() no longer wakes the thread, and the caller sends with send_queued() (the thread still sends what is
  // left each 100 ms). Off: the thread sends, woken by each commit (the default).
  void send_here(bool on) { send_here_.store(on, std::memory_order_relaxed); }
  bool sends_here() const { return send_here_.load(std::memory_order_relaxed); }
  // Sends what is queued on the calling thread, unless the outbox's thread is sending at that moment (it then sends
  // them); the number sent. Waits on the socket and may grow a slot: not for a real-time loop.
  size_t send_queued();

  // Waits until everything committed before the call has been sent (not for the loop path).
  void flush();
  int64_t dropped() const { return dropped_.load(std::memory_order_relaxed); }
  int64_t sent() const { return sent_.load(std::memory_order_relaxed); }

 private:
  void run();
  size_t send_from_tail();  // holding consuming_


  std::vector<Slot> slots_;
  Send send_;
  std::atomic<uint64_t> head_{0};  // next slot to fill: written by the producer
  std::atomic<uint64_t> tail_{0};  // next slot to send: written by the sending thread
  std::atomic_flag producing_ = ATOMIC_FLAG_INIT;
  std::atomic_flag consuming_ = ATOMIC_FLAG_INIT;  // held by whichever thread sends: the outbox's or send_queued's
  std::atomic<bool> sleeping_{false}, stop_{false}, send_here_{false};
  std::atomic<size_t> largest_{0};  // the biggest message so far: the sending thread grows the slots it frees to it
  std::atomic<int64_t> dropped_{0}, sent_{0};
  int wake_fd_ = -1;
  std::thread thread_;
};

}  // namespace lcm_control
