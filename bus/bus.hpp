// LCM plumbing both processes and the tools share: the URL (flag, else
// LCM_DEFAULT_URL), namespaced channel names, and checked LCM instances: the
// shared bus, and the hardware loop's own when it is given one.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include "bus/bus_error.hpp"
#include "bus/lcm_socket.hpp"
#include "bus/shm_link.hpp"
#include "bus/wire_check.hpp"
#include "rt/clock.hpp"

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace lcm_control {

// Well-known channel names (before the namespace prefix).
namespace channels {
inline constexpr const char* kJointStates = "joint_states";
inline constexpr const char* kHardwareState = "hardware/state";
inline constexpr const char* kHardwareCommand = "hardware/command";
inline constexpr const char* kCmRequest = "controller_manager/request";
inline constexpr const char* kCmConfig = "controller_manager/config";  // run_config_t: what the run was started with
inline constexpr const char* kCmResponse = "controller_manager/response";
inline constexpr const char* kCmStatistics = "controller_manager/statistics";
inline constexpr const char* kCmInputs = "controller_manager/inputs";  // cm_inputs_t: what each cycle took in
inline constexpr const char* kCmCommandSource = "controller_manager/command_source";
inline constexpr const char* kCmActivity = "controller_manager/activity";
inline constexpr const char* kSimStatistics = "sim_server/statistics";
inline constexpr const char* kSimGainsOwner = "sim_server";
inline constexpr const char* kSimRequest = "sim_server/request";
inline constexpr const char* kSimConfig = "sim_server/config";  // run_config_t: what sim_server was started with
inline constexpr const char* kSimResponse = "sim_server/response";
inline constexpr const char* kEStop = "e_stop";
inline constexpr const char* kClock = "clock";
inline constexpr const char* kLinkPoses = "link_poses";
inline constexpr const char* kBasePose = "sim_server/base_pose";
}  // namespace channels

// "<owner>/gains/set" and "<owner>/gains".
std::string gains_set_channel(const std::string& owner);
std::string gains_channel(const std::string& owner);

// The URL of a robot's hardware loop (hardware/state, hardware/command) for `--hardware-url VALUE`:
// "" or "shared" = the shared bus itself; "auto" = the shared udpm URL with its port moved to one the namespace picks
// (kHardwarePortBase + FNV-1a(ns) % kHardwarePorts), so that every robot's loop has its own socket and the
// processes on the shared bus do not wake for it; "shm" = shared memory on this host, a segment per namespace
// ("shm:NAME" as resolved, bus/shm_link.hpp), and "shm:NAME" that segment; anything else is used as given. Throws
// BusError when auto meets a URL that is not udpm://, or a shm name is not one.
inline constexpr int kHardwarePortBase = 7700, kHardwarePorts = 2000;
std::string hardware_url_for(const std::string& value, const std::string& shared_url, const std::string& ns);

// The URL in effect for `url` "" (LCM_DEFAULT_URL, else LCM's default).
std::string effective_url(const std::string& url);

// How a program receives. Lcm: LCM's receive thread hands each message over through its pipe; LCM keeps an entry for
// every channel name it ever received, for good. Direct (every long-running program; on udpm:// URLs, Lcm
// elsewhere): LcmSocket, read on the program's own thread, for the shared bus and the hardware loop's own URL, so
// that what is kept per channel name is bounded (docs/reliability.md, "Limits"); when the hardware loop travels on
// the shared bus, one socket keeps the order in which everything was sent (an e-stop or gains published before a
// command act before it). Publishing goes through lcm::LCM always.
enum class HardwareReader { Lcm, Direct };
HardwareReader hardware_reader_named(const std::string& name);

// A namespace prefix "NS/" (empty for none) applied to every channel name.
class Bus {
 public:
  // url "" means LCM_DEFAULT_URL, else LCM's default; hardware_url as hardware_url_for() takes it. Throws BusError
  // with the URL and the multicast-route fix when LCM cannot start, or when a Direct reader's own test datagram
  // does not come back.
  Bus(const std::string& url, const std::string& ns, const std::string& hardware_url = "",
      HardwareReader reader = HardwareReader::Lcm);
  ~Bus();

  // Where a subscription listens: the shared bus, or the hardware loop (hardware/state, hardware/command).
  enum class On { Shared, Hardware };

  // Every message on a channel `pattern` matches whole (a regular expression, as lcm::LCM::subscribe takes it) goes
  // to `handler`, in the thread that calls handle(): from the socket read directly when there is one (then the
  // kernel's receive buffer is the queue), else through LCM, which holds up to `queue` messages (0: no limit).
  // Until unsubscribe(id). Throws BusError when `pattern` is not a regular expression.
  using ChannelHandler = LcmSocket::ChannelHandler;
  int subscribe(const std::string& pattern, ChannelHandler handler, On on = On::Shared, int queue = 1000);
  template <class Obj>
  int subscribe(const std::string& pattern, void (Obj::*fn)(const lcm::ReceiveBuffer*, const std::string&), Obj* obj,
                On on = On::Shared, int queue = 1000) {
    return subscribe(
        pattern, [fn, obj](const lcm::ReceiveBuffer& rb, const std::string& channel) { (obj->*fn)(&rb, channel); }, on,
        queue);
  }
  void unsubscribe(int id);

  lcm::LCM& lcm() { return *lcm_; }
  // Where hardware/state and hardware/command travel: lcm() unless the hardware loop has its own URL (on shared
  // memory, lcm() too: the mirror's).
  lcm::LCM& hardware() { return hw_ ? *hw_ : *lcm_; }
  bool hardware_apart() const { return hw_ != nullptr || shm_ != nullptr; }
  const std::string& hardware_url() const { return hardware_apart() ? hw_url_ : url_; }
  // The sockets read directly (HardwareReader::Direct on udpm://), else null: subscribe there instead of on lcm()
  // or hardware(). The same socket when the hardware loop travels on the shared bus; none on shared memory.
  LcmSocket* shared_socket() { return shared_socket_.get(); }
  LcmSocket* hardware_socket() { return shm_ ? nullptr : hw_ ? hw_socket_.get() : shared_socket_.get(); }
  // The hardware loop's shared memory (--hardware-url shm), else null: publish and subscribe there.
  ShmLink* hardware_shm() { return shm_.get(); }
  // Shared memory: what is published on the hardware loop is also sent on the shared bus, at most `hz` times a
  // second per channel (0: not at all, the default), for the tools that listen there.
  void mirror_hardware(double hz);
  // Messages on the hardware loop skipped before any handler saw them: over shared memory, a slot whose size word is
  // past the slot (ShmLink::malformed()); 0 on LCM. Counted with the programs' dropped messages.
  int64_t hardware_skipped() const { return shm_ ? shm_->malformed() : 0; }
  // Messages this process could not put on the hardware loop's shared memory: over its 1 MiB slot
  // (ShmLink::too_large()); 0 on LCM.
  int64_t hardware_refused() const { return shm_ ? shm_->too_large() : 0; }
  // A line naming the segment and what to do for each of hardware_skipped() and hardware_refused() that grew since
  // the last call, and for what another process did to the segment (ShmLink::take_tampering_note()), else "".
  std::string hardware_loss_note();
  // The file descriptors to wait on: the shared bus's, then the hardware loop's when it has a URL of its own (on
  // shared memory, the shared bus's only: wait_us() waits on both).
  std::vector<int> fds();
  // Waits up to timeout_us for a message on either: kSharedReady | kHardwareReady for where one is, 0 when the time
  // ran out or a signal came, -1 on an error.
  static constexpr int kSharedReady = 1, kHardwareReady = 2;
  int wait_us(int64_t timeout_us);
  // The same until monotonic_us() reaches deadline_us (over shared memory without reading the clock).
  int wait_until_us(int64_t deadline_us);
  // Handle what is queued (at most `max` messages) without blocking: how many, -1 on an error.
  int handle_shared(int max = 1000);
  // A pass of handle_shared() reads the shared bus's socket for at most this long (0, the default: no bound), so that
  // a large message arriving in many fragments (a 4 MiB trajectory goal) is read over several passes, with the
  // hardware loop's own socket looked at between them. Only where the socket is read directly.
  void set_pass_budget_us(int64_t us) { pass_budget_us_ = us; }
  int handle_hardware(int max = 1000);
  const std::string& url() const { return url_; }
  const std::string& ns() const { return ns_; }
  std::string channel(const std::string& name) const { return prefix_ + name; }

  template <class Msg>
  int publish(const std::string& name, const Msg& msg) {
    return lcm_->publish(channel(name), &msg);
  }

  // Waits up to timeout_ms for messages on either instance and handles what is queued there, the hardware loop
  // first: at most `max` from each (one by default, so that a tool can stop after any message; the controller
  // manager drains a backlog before its housekeeping); false on an error.
  bool handle(int timeout_ms, int max = 1) { return handle_us(int64_t{timeout_ms} * 1000, max); }
  // The same with the wait in microseconds (0: what is queued now, without sleeping). Through LCM's receive thread
  // (no socket read directly) the wait is rounded up to whole milliseconds.
  bool handle_us(int64_t timeout_us, int max = 1);

 private:
  int shared_fd();
  int hardware_fd();  // -1 without a hardware URL of its own
  int ready(bool woken);  // wait_us()'s result from the shared memory's wait
  std::unique_ptr<lcm::LCM> lcm_, hw_;
  std::unique_ptr<LcmSocket> shared_socket_, hw_socket_;
  std::unique_ptr<ShmLink> shm_;
  std::string url_, ns_, prefix_, hw_url_;
  struct Subscription {
    int id = 0, socket_id = 0;
    LcmSocket* socket = nullptr;
    ShmLink* shm = nullptr;
    lcm::LCM* lc = nullptr;
    lcm::Subscription* lcm_sub = nullptr;
    ChannelHandler handler;
    void on(const lcm::ReceiveBuffer* rb, const std::string& channel) { handler(*rb, channel); }
  };
  std::vector<std::unique_ptr<Subscription>> subscriptions_;
  int64_t skipped_noted_ = 0, refused_noted_ = 0;
  int64_t pass_budget_us_ = 0;  // set_pass_budget_us()
};

namespace detail {
// lcm-gen's decoder resizes an array only when its count is not 0: decoded into a reused message, an array whose count
// is 0 keeps the previous message's elements. Cuts every array, nested ones too, to its count (no allocation).
class FitArraysToCounts {
 public:
  template <class T>
  void value(const char*, T&) {}
  void count(const char* name, int32_t& n) {
    if (num_counts_ < counts_.size()) counts_[num_counts_++] = {name, n};
  }
  template <class T>
  void list(const char*, std::vector<T>& v, const char* counter) {
    v.resize(count_of(counter));
  }
  template <class T>
  void matrix(const char*, std::vector<std::vector<T>>& v, const char* counter, int) {
    v.resize(count_of(counter));
  }
  template <class S>
  void structs(const char*, std::vector<S>& v, const char* counter) {
    v.resize(count_of(counter));
    for (S& x : v) nested("", x);
  }
  template <class S>
  void nested(const char*, S& x) {
    FitArraysToCounts inner;
    visit(x, inner);
  }

 private:
  size_t count_of(const char* counter) const {
    for (size_t k = 0; k < num_counts_; ++k)
      if (std::strcmp(counts_[k].first, counter) == 0) return counts_[k].second > 0 ? size_t(counts_[k].second) : 0;
    return 0;
  }
  std::array<std::pair<const char*, int32_t>, 8> counts_{};
  size_t num_counts_ = 0;
};
}  // namespace detail

// lcm-gen's decode of bytes the schema walk (wire_fits or wire_problem) has accepted, every array then exactly as long
// as its count; false if it still fails or throws. Only for bytes already walked: decode_guarded is the one to call
// otherwise.
template <class Msg>
bool decode_walked(Msg& msg, const void* data, size_t size) noexcept {
  try {
    if (msg.decode(data, 0, int(size)) < 0) return false;
    detail::FitArraysToCounts fit;
    visit(msg, fit);
    return true;
  } catch (const std::exception&) {
    msg = Msg();
    return false;
  }
}

// Decodes bytes from the bus into msg; false when they are not a Msg: a count or length that does not fit the bytes
// (checked by wire_fits before lcm-gen's decoder, which would allocate what the count says), or a decoder that throws.
// Every decode of bus input goes through here.
template <class Msg>
bool decode_guarded(Msg& msg, const void* data, size_t size) noexcept {
  return wire_fits<Msg>(data, size) && decode_walked(msg, data, size);
}

namespace detail {
template <auto Handler>
struct GuardedHandler;
template <class Obj, class Msg, void (Obj::*Handler)(const lcm::ReceiveBuffer*, const std::string&, const Msg*)>
struct GuardedHandler<Handler> {
  static void on(const lcm::ReceiveBuffer* rb, const std::string& channel, Obj* obj) {
    Msg m;
    if (decode_guarded(m, rb->data, rb->data_size)) (obj->*Handler)(rb, channel, &m);
  }
};
}  // namespace detail

// lcm::LCM::subscribe(channel, &Obj::handler, obj) for a typed handler, with the decode guarded: bytes that are
// not a Msg never reach it. Use: subscribe_guarded<&Obj::on_state>(lc, channel, this).
template <auto Handler, class Obj>
lcm::Subscription* subscribe_guarded(lcm::LCM& lc, const std::string& channel, Obj* obj) {
  return lc.subscribeFunction(channel, &detail::GuardedHandler<Handler>::on, obj);
}
// The same through Bus::subscribe (the bus's own reader): an id for Bus::unsubscribe.
template <auto Handler, class Obj>
int subscribe_guarded(Bus& bus, const std::string& channel, Obj* obj, Bus::On on = Bus::On::Shared, int queue = 1000) {
  return bus.subscribe(
      channel,
      [obj](const lcm::ReceiveBuffer& rb, const std::string& ch) { detail::GuardedHandler<Handler>::on(&rb, ch, obj); },
      on, queue);
}

}  // namespace lcm_control
