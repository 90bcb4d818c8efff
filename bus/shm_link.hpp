// The hardware loop over shared memory between processes on one host (--hardware-url shm[:NAME]): each channel
// (hardware/state, hardware/command) is a single slot holding its newest message as LCM encodes it, so the
// receivers run the same schema walk on the same bytes; a writer rings each reader's futex. A file in /dev/shm,
// created by the first process, reused by the next, removed by the last one to close it (a killed one too: the kernel
// drops its lock). No daemon, no thread on the hot path, nothing allocated once the slots are bound.
// Why not iceoryx (libiceoryx-posh-dev 2.0.3), measured on this machine: its WaitSet round trip between two
// processes on one CPU is 8.1 us at the median, a futex's 2.6 us (docs/hardware-protocol.md, "Over shared memory").
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bus/lcm_socket.hpp"

namespace lcm_control {

class ShmLink {
 public:
  static constexpr int kSlots = 4;        // channels one segment carries
  static constexpr int kReaders = 8;      // processes attached at once
  static constexpr uint32_t kSlotBytes = 1u << 20;  // the largest message a slot holds
  static constexpr size_t kChannelBytes = 256;

  // The segment of `name` (/dev/shm/lcm_control.NAME), created when no process has it open. Throws BusError naming
  // the file and what to do when it cannot be opened, is not ours, or has no reader place left.
  explicit ShmLink(const std::string& name);
  ~ShmLink();
  ShmLink(const ShmLink&) = delete;
  ShmLink& operator=(const ShmLink&) = delete;

  const std::string& path() const { return path_; }

  // The newest message on `channel` is now these bytes; each other process subscribed to it is woken. -1 when the
  // message is over kSlotBytes (counted: too_large()) or the segment has no slot left for a new channel.
  int publish(const std::string& channel, const void* data, size_t size);

  // Messages on `channel` from other processes go to `handler` (recv_utime: the wall clock when it was taken) in the
  // thread that calls handle_queued(); a message overwritten before it was taken is not seen (the slot keeps the
  // newest, as a real-time loop wants it). An id for unsubscribe().
  using Handler = std::function<void(const lcm::ReceiveBuffer&)>;
  int subscribe(const std::string& channel, Handler handler);
  // The same for every channel `pattern` (a ChannelPattern) matches, checked as slots are bound. Throws BusError when
  // it is not a regular expression.
  using ChannelHandler = std::function<void(const lcm::ReceiveBuffer&, const std::string& channel)>;
  int subscribe_pattern(const std::string& pattern, ChannelHandler handler);
  void unsubscribe(int id);

  // Hands over the messages not taken yet, at most `max`: how many.
  int handle_queued(int max = 1000);
  // True when a subscribed slot holds a message not taken yet.
  bool has_new();

  // Waits up to timeout_us for a message on a subscribed channel or a watched file descriptor becoming readable:
  // true unless the time ran out or a signal came. Never longer than timeout_us, so a dead writer cannot hold it.
  bool wait_us(int64_t timeout_us);
  // The same until monotonic_us() reaches deadline_us.
  bool wait_until_us(int64_t deadline_us);

  // Lockstep, where the peer answers at once (on this CPU, as launch pins them): waits first hand it the CPU with
  // sched_yield, for up to kYieldUs, before sleeping on the futex. A hand-over then costs a yield instead of a futex
  // wake and wait. A wait the yields did not end sleeps at once from then on, until one ends within kYieldUs: a
  // paused or dead peer costs no CPU. Off by default (real time sleeps until its deadline).
  static constexpr int64_t kYieldUs = 1000;
  void yield_first(bool on) { yield_first_ = on; }
  bool yields_next() const { return yield_first_ && peer_prompt_; }  // whether the next wait yields before sleeping

  // A thread of its own polls `fd` and ends wait_us() when it is readable: fd_ready() says so until fd_drained(),
  // after which it polls again. For the shared bus's socket, so that one wait covers both.
  void watch_fd(int fd);
  bool fd_ready() const { return fd_ready_.load(std::memory_order_acquire) != 0; }
  void fd_drained();

  // Every message published is also sent on `lcm` (its channel, the same bytes) at most `hz` times a second of wall
  // time per channel, for lcm-spy, bus, the dashboard and the logger; 0: none.
  void mirror_to(lcm::LCM* lcm, double hz);

  int64_t malformed() const { return malformed_; }  // a slot whose size is not a message size: skipped
  int64_t too_large() const { return too_large_; }  // publish() refused: over kSlotBytes
  int64_t stolen() const { return stolen_; }        // a slot taken over from a writer that died while writing

  // What another process did to the segment, each kind said once, "" when nothing new: the file truncated under
  // this process (its pages then read as zeros instead of raising SIGBUS: the loop is lost, as on a lost peer), this
  // process's reader place rewritten (restored), a slot held mid-write past kStuckUs, a channel written by two live
  // processes. Detected on the hot path with flags only; the text is made here.
  std::string take_tampering_note();

 private:
  struct Segment;
  int slot_of(const std::string& channel, bool claim);
  void bind_slots();  // matches subscriptions to the slots other processes have bound since
  void ring(int slot);
  void mirror(int slot, const std::string& channel, const void* data, size_t size);  // to mirror_, at most its rate
  bool truncated() const;  // the file shrank under this mapping: zeros are mapped in its place
  void check_place();      // restores this process's reader place if another process rewrote it
  void ring_self();
  void update_mask();
  // Whether slot `s` holds a message for this process not taken yet (subscribed, written whole, by another process),
  // its sequence in `seq`; marks this process's own messages taken.
  bool news(int s, uint32_t& seq);
  bool take(int slot, uint32_t seq);
  bool sleep_until(const timespec& until);  // on this process's futex (CLOCK_MONOTONIC)

  std::string path_;
  int fd_ = -1;
  Segment* seg_ = nullptr;
  uint8_t* data_ = nullptr;
  int me_ = -1;  // this process's reader place
  int32_t pid_ = 0;

  struct Sub {
    int id;
    std::optional<ChannelPattern> pattern;  // none: one channel, bound when subscribed
    Handler handler;
    ChannelHandler channel_handler;
  };
  std::vector<Sub> subs_;
  std::vector<int> slot_subs_[kSlots];  // indices into subs_ per slot
  std::string slot_name_[kSlots];
  bool bound_[kSlots] = {};
  uint32_t seen_[kSlots] = {};
  uint32_t names_seen_ = 0;  // the segment's count of named slots when bind_slots() last ran
  std::vector<uint8_t> buf_;
  int next_id_ = 1;

  lcm::LCM* mirror_ = nullptr;
  int64_t mirror_period_us_ = 0, mirrored_us_[kSlots] = {};

  bool yield_first_ = false;
  bool peer_prompt_ = true;  // the last wait ended within kYieldUs
  std::atomic<uint32_t> fd_ready_{0};
  std::atomic<bool> stop_watch_{false};
  int watch_stop_fd_ = -1;
  std::thread watcher_;
  int64_t malformed_ = 0, too_large_ = 0, stolen_ = 0;

  // Tampering seen, for take_tampering_note(): set on the hot path, said once each.
  uint32_t mask_ = 0;  // the reader mask this process set
  bool place_rewritten_ = false, place_said_ = false;
  int64_t odd_since_us_[kSlots] = {-1, -1, -1, -1};
  uint32_t odd_seq_[kSlots] = {};
  bool odd_held_[kSlots] = {}, odd_said_[kSlots] = {};
  int last_writer_[kSlots] = {-1, -1, -1, -1};
  int32_t two_writers_[kSlots][2] = {};  // their pids, once seen
  bool two_said_[kSlots] = {};
  int mapping_ = -1;  // this segment's place in the SIGBUS handler's table
  bool truncated_said_ = false;
};

// The segment name for `--hardware-url` "shm" (the namespace's, per user) or "shm:NAME"; "" when the URL is not
// shared memory. Throws BusError when NAME holds characters other than letters, digits, '.', '_' and '-'.
std::string shm_name_of(const std::string& hardware_url, const std::string& ns);
bool is_shm_url(const std::string& url);

}  // namespace lcm_control
