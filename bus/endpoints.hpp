// The bus layer both processes use: the LCM endpoints of one owner (a controller, the services, sim_server's I/O):
// subscriptions that decode into a message kept between calls (no allocation once warm) and are removed with the
// Endpoints, on LCM's thread or on a socket read directly (Bus::shared_socket(), hardware_socket()), subscriptions
// whose large messages are decoded and prepared off the loop (rt/intake.hpp), and publishers that encode into a
// reused buffer, or into an Outbox's slot (rt/outbox.hpp).
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <lcm/lcm-cpp.hpp>
#include <memory>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "bus/lcm_socket.hpp"
#include "rt/intake.hpp"
#include "rt/outbox.hpp"

namespace lcm_control {

// Encodes m into buf (grown only when m outgrew it); the encoded size, or -1.
template <class Msg>
int encode_into(const Msg& m, std::vector<uint8_t>& buf) {
  int n = m.encode(buf.data(), 0, static_cast<int>(buf.size()));  // the size is computed only when it grew
  if (n < 0) {
    buf.resize(static_cast<size_t>(m.getEncodedSize()));
    n = m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  }
  return n;
}

// Publishes one message type on one channel: sent at once, written to the hardware loop's shared memory when it
// travels there, or handed to an Outbox when it has one (the loop path then never touches a socket). After the
// first message of a given size it neither allocates nor formats.
template <class Msg>
class Publisher {
 public:
  Publisher() = default;
  Publisher(lcm::LCM* lc, std::string channel, Outbox* outbox = nullptr, ShmLink* shm = nullptr)
      : lc_(lc), outbox_(shm ? nullptr : outbox), shm_(shm), channel_(std::move(channel)) {
    if (!outbox_) buf_.resize(256);
  }
  bool valid() const { return lc_ != nullptr; }
  const std::string& channel() const { return channel_; }
  // 0, or -1: not encodable, or dropped by the outbox (counted there).
  int publish(const Msg& m) {
    if (outbox_) {
      Outbox::Slot* s = outbox_->begin();
      if (!s) return -1;
      const int n = encode_into(m, s->bytes);
      if (n < 0) {
        outbox_->abandon();
        return -1;
      }
      s->channel = channel_;
      s->size = static_cast<size_t>(n);
      outbox_->commit();
      return 0;
    }
    const int n = encode_into(m, buf_);
    if (n < 0) return -1;
    if (shm_) return shm_->publish(channel_, buf_.data(), static_cast<size_t>(n));
    return lc_->publish(channel_, buf_.data(), static_cast<unsigned>(n));
  }

 private:
  lcm::LCM* lc_ = nullptr;
  Outbox* outbox_ = nullptr;
  ShmLink* shm_ = nullptr;
  std::string channel_;
  std::vector<uint8_t> buf_;
};

class Endpoints {
 public:
  // Publishes on lc and subscribes on `socket` when it is not null (read directly), else on lc; both on `shm` when it
  // is not null.
  explicit Endpoints(lcm::LCM& lc, LcmSocket* socket = nullptr, ShmLink* shm = nullptr)
      : lc_(lc), socket_(socket), shm_(shm) {}
  // On the bus's shared channels, or on its hardware loop (hardware/state, hardware/command).
  using On = Bus::On;
  Endpoints(Bus& bus, On on)
      : Endpoints(on == On::Shared ? bus.lcm() : bus.hardware(),
                  on == On::Shared ? bus.shared_socket() : bus.hardware_socket(),
                  on == On::Shared ? nullptr : bus.hardware_shm()) {}
  ~Endpoints();
  Endpoints(const Endpoints&) = delete;
  Endpoints& operator=(const Endpoints&) = delete;

  lcm::LCM& lcm() { return lc_; }

  // Raw bytes; the handler runs in the thread that calls handle().
  void subscribe_raw(const std::string& channel, std::function<void(const lcm::ReceiveBuffer&)> handler);

  // "" when raw bytes may be decoded, else why not: the schema walk of bus/wire_check.hpp (wire_problem, with
  // a tighter bound on the counts), which then replaces decode_guarded's own walk.
  using Precheck = std::function<std::string(const void* data, size_t size)>;

  // Decodes into a message kept by the Endpoints; on_bad gets the reason when the
  // bytes are not a Msg (precheck refused them, or the decoder failed or threw).
  template <class Msg>
  void subscribe(const std::string& channel, std::function<void(const Msg&)> on_msg,
                 std::function<void(const std::string&)> on_bad = {}, Precheck precheck = {}) {
    subscribe_decoded<Msg>(channel, std::move(on_msg), std::move(on_bad), true, std::move(precheck));
  }

  // As subscribe(), into a new Msg each time (allocates): for types whose arrays
  // may be empty, such as a trajectory point's optional velocities. LCM 1.3.1's
  // decode leaves an array whose count is 0 as it was, so a kept message would
  // still hold the previous message's values there.
  template <class Msg>
  void subscribe_fresh(const std::string& channel, std::function<void(const Msg&)> on_msg,
                       std::function<void(const std::string&)> on_bad = {}) {
    subscribe_decoded<Msg>(channel, std::move(on_msg), std::move(on_bad), false, {});
  }

  // For messages too large to take in between two cycles (trajectory goals): the bytes are kept (moved out of the
  // socket's buffer when it put them together: LcmSocket::take_delivered, and given back to its pool once decoded),
  // decoded into a new Msg and given to `prepare` on the intake's thread (set_intake); what prepare returns runs on
  // the loop's thread at the intake's next drain, held as the handlers are while busy() (hold_while). Without an intake, or with one in place,
  // everything runs in the handler. on_bad: as subscribe(), on the loop's thread. prepare must not touch what the
  // loop uses (capture copies, or what is never changed).
  template <class Msg>
  void subscribe_off_loop(const std::string& channel, std::function<Intake::Result(const Msg&)> prepare,
                          std::function<void(const std::string&)> on_bad = {}) {
    if (on_bad) on_lost(channel, [on_bad](const LcmSocket::Lost& lost) { on_bad(describe(lost)); });
    subscribe_raw(channel, [this, prepare, on_bad, channel](const lcm::ReceiveBuffer& rb) {
      std::vector<uint8_t> bytes =
          socket_ ? socket_->take_delivered(rb)
                  : std::vector<uint8_t>(static_cast<const uint8_t*>(rb.data),
                                         static_cast<const uint8_t*>(rb.data) + rb.data_size);
      std::weak_ptr<char> life = life_;
      std::shared_ptr<BytePool> pool = socket_ ? socket_->pool() : nullptr;
      Intake::Job job = [this, life, pool, bytes = std::move(bytes), prepare, on_bad,
                         channel]() mutable -> Intake::Result {
        Intake::Result result;
        {
          Msg msg;
          if (decode_guarded(msg, bytes.data(), bytes.size())) {
            result = prepare(msg);
          } else if (on_bad) {
            result = [on_bad, why = "could not decode " + std::to_string(bytes.size()) + " bytes on '" + channel +
                                    "' as " + Msg::getTypeName()] { on_bad(why); };
          }
        }  // the message is freed here, on the intake's thread
        if (pool) pool->give_back(std::move(bytes));  // the next large message is put together in their room
        if (!result) return {};
        return [this, life, result = std::move(result)]() mutable {
          if (life.lock()) deliver_result(std::move(result));
        };
      };
      if (intake_) {
        intake_->submit(std::move(job));
      } else if (Intake::Result r = job()) {
        r();
      }
    });
  }
  // subscribe_off_loop() prepares on this intake's thread from now on (nullptr: in the handler).
  void set_intake(Intake* intake) { intake_ = intake; }
  // Frees `garbage` on the intake's thread (here without one): a replaced trajectory of 100,000 points.
  template <class T>
  void dispose(T&& garbage) {
    if (intake_) intake_->dispose(std::forward<T>(garbage));
  }

  // A message on `channel` lost on the way, too large or with fragments missing (bus/lcm_socket.hpp): `handler`
  // hears of it. Only where the Endpoints read a socket directly: lcm::LCM drops such messages unseen.
  void on_lost(const std::string& channel, LcmSocket::LostHandler handler);

  using RawHandler = std::function<void(const lcm::ReceiveBuffer&)>;
  // While diverted, what arrives from the bus on `channel` goes to `to` (once) instead of its handlers: a command
  // source owns the channel. An empty `to` gives the channel back.
  void divert(const std::string& channel, RawHandler to);
  // While `busy()` says so, what arrives for these handlers (but a diverted channel) is kept, copied, instead of
  // delivered: an is_async controller's handlers must not run while its update does. deliver_held() delivers it, in
  // the order it came, when not busy; beyond kHeldMax messages the oldest are dropped (held_dropped()).
  static constexpr size_t kHeldMax = 1000;
  void hold_while(std::function<bool()> busy) { busy_ = std::move(busy); }
  size_t deliver_held();
  size_t held() const { return held_.size() + held_results_.size(); }
  int64_t held_dropped() const { return held_dropped_; }
  // Every channel subscribed, in subscription order (tests send to each).
  std::vector<std::string> channels() const;

  // Publishers made from now on hand their messages to `outbox` (nullptr: they send at once).
  void set_outbox(Outbox* outbox) { outbox_ = outbox; }

  template <class Msg>
  Publisher<Msg> publisher(const std::string& channel) {
    return Publisher<Msg>(&lc_, channel, outbox_, shm_);
  }

 private:
  template <class Msg>
  void subscribe_decoded(const std::string& channel, std::function<void(const Msg&)> on_msg,
                         std::function<void(const std::string&)> on_bad, bool keep, Precheck precheck) {
    if (on_bad) on_lost(channel, [on_bad](const LcmSocket::Lost& lost) { on_bad(describe(lost)); });
    auto kept = std::make_shared<Msg>();
    subscribe_raw(channel, [kept, keep, on_msg, on_bad, channel, precheck](const lcm::ReceiveBuffer& rb) {
      auto bad = [&](const std::string& why) {
        if (on_bad)
          on_bad("could not decode " + std::to_string(rb.data_size) + " bytes on '" + channel + "' as " +
                 Msg::getTypeName() + (why.empty() ? "" : ": " + why));
      };
      if (precheck) {
        if (const std::string why = precheck(rb.data, rb.data_size); !why.empty()) return bad(why);
      }
      Msg fresh;
      Msg& msg = keep ? *kept : fresh;
      if (!(precheck ? decode_walked(msg, rb.data, rb.data_size) : decode_guarded(msg, rb.data, rb.data_size)))
        return bad("");
      on_msg(msg);
    });
  }

  struct Handler {
    RawHandler fn;
    std::string channel;
    RawHandler diverted;
    bool muted = false;  // diverted through another handler of the same channel
    Endpoints* ends = nullptr;
    void deliver(const lcm::ReceiveBuffer& rb) {
      if (diverted)
        diverted(rb);
      else if (muted)
        return;
      else if (ends->busy_ && ends->busy_())
        ends->hold(*this, rb);
      else
        fn(rb);
    }
    void on(const lcm::ReceiveBuffer* rb, const std::string&) { deliver(*rb); }
  };
  struct Held {
    Handler* handler;
    std::vector<uint8_t> bytes;
    int64_t recv_utime;
  };
  void hold(Handler& h, const lcm::ReceiveBuffer& rb);
  void deliver_result(Intake::Result result);
  std::function<bool()> busy_;
  std::deque<Held> held_;
  std::deque<Intake::Result> held_results_;  // results of subscribe_off_loop held while busy
  Intake* intake_ = nullptr;
  std::shared_ptr<char> life_ = std::make_shared<char>();  // results of jobs outliving the Endpoints are dropped
  int64_t held_dropped_ = 0;
  lcm::LCM& lc_;
  LcmSocket* socket_ = nullptr;
  ShmLink* shm_ = nullptr;
  Outbox* outbox_ = nullptr;
  std::vector<std::unique_ptr<Handler>> handlers_;
  std::vector<lcm::Subscription*> subs_;
  std::vector<int> socket_subs_, shm_subs_;
};

}  // namespace lcm_control
