// LCM's udpm datagrams read on the calling thread, for the hardware loop: no LCM receive thread, no pipe and no
// queue between the socket and the handler, so each hop of a lockstep exchange costs one thread wake-up less
// (bench/README.md, "Below the floor"). The tools and the loops' shared bus are read through it too
// (HardwareReader::Direct): unlike LCM's receive path, it keeps nothing for good per channel name. The packets are LCM's own (lcm::LCM publishes them), so lcm-spy,
// lcm-logger and lcm-logplayer see and replay the same messages.
// While every subscription names its channel (no pattern operator), a kernel socket filter admits only whole messages
// on those channels (and every fragment, and what is not LCM's): a datagram nobody here reads neither wakes the
// program nor takes room in its receive buffer, however busy the bus is with other robots and tools.
// A message LCM sends whole ("LC02") is handed over from the receive buffer; one it split into "LC03" fragments
// (over 64 kB with Debian's LCM, over 1,400 bytes with some other builds) is put together first, as LCM does: one
// message in progress per sender, its fragments in the order LCM sends them. What a forged or broken sender can
// make it hold is bounded: a message announcing more than kMaxMessageBytes is refused at its first fragment, a
// message takes memory only as its fragments arrive, one unheard for kFragmentTimeoutUs is dropped, and a buffer
// over kKeptBytes is given back once its message is delivered or dropped. A subscriber that asks is told of each
// message on its channel that was lost this way (docs/reliability.md, "Limits").
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <netinet/in.h>
#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "rt/byte_pool.hpp"

namespace lcm_control {

// udpm://GROUP:PORT?ttl=N&recv_buf_size=N taken apart as LCM reads it (defaults 239.255.76.67, 7667, ttl 0).
struct UdpmAddress {
  std::string group = "239.255.76.67";
  int port = 7667;
  int ttl = 0;
  int recv_buf_size = 0;  // 0: the kernel's default
};
// Throws BusError naming the URL when it is not a udpm:// URL LCM would take.
UdpmAddress parse_udpm_url(const std::string& url);

// A channel pattern as lcm::LCM::subscribe takes it: a POSIX extended regular expression matched against the whole
// channel name. Shared by the readers of LCM's sockets and of the hardware loop's shared memory.
class ChannelPattern {
 public:
  // Throws BusError naming the pattern and `where` (the URL or file read) when it is not a regular expression.
  ChannelPattern(const std::string& pattern, const std::string& where);
  bool matches(const char* channel) const;
  // The one channel name the pattern matches when it has no operator (backslash escapes undone), else none.
  const std::optional<std::string>& literal() const { return literal_; }

 private:
  std::shared_ptr<const void> regex_;  // the compiled regex_t
  std::optional<std::string> literal_;
};

class LcmSocket {
 public:
  // Joins the URL's group on its port beside any other LCM socket there. Throws BusError with the URL and the fix.
  explicit LcmSocket(const std::string& url);
  ~LcmSocket();
  LcmSocket(const LcmSocket&) = delete;
  LcmSocket& operator=(const LcmSocket&) = delete;

  int fd() const { return fd_; }
  const std::string& url() const { return url_; }

  // Messages on `channel` (the exact name) go to `handler` with LCM's ReceiveBuffer (recv_utime: the wall clock
  // when the datagram arrived, the kernel's SO_TIMESTAMP as LCM's own receive thread gives it), until unsubscribe() with the id returned (unique in the process). Not from inside a handler.
  using Handler = std::function<void(const lcm::ReceiveBuffer&)>;
  int subscribe(const std::string& channel, Handler handler);
  void unsubscribe(int id);

  // A fragmented message on a subscribed channel that was not delivered.
  struct Lost {
    std::string_view channel;
    uint32_t bytes = 0;          // the message's size as its fragments announced it
    bool too_large = false;      // over kMaxMessageBytes: refused at its first fragment; else fragments went missing
    const uint8_t* head = nullptr;  // the message's first head_size bytes as they arrived (for its ids), or none
    int head_size = 0;
  };
  using LostHandler = std::function<void(const Lost&)>;
  // `handler` hears of the messages on `channel` lost as above, in the thread that calls handle_queued(); as
  // subscribe(), until unsubscribe(id).
  int on_lost(const std::string& channel, LostHandler handler);

  // Messages on every channel `pattern` matches whole (a POSIX extended regular expression, as lcm::LCM::subscribe
  // takes it: ".*" for all) go to `handler` with their channel name, as subscribe(). Which subscriptions a channel
  // matches is remembered for at most kMatchedChannels names, then forgotten and worked out again: unlike LCM's
  // receive path, which keeps every name it ever received, a sender of ever new names costs no memory here.
  // Throws BusError naming the pattern when it is not a regular expression.
  using ChannelHandler = std::function<void(const lcm::ReceiveBuffer&, const std::string& channel)>;
  int subscribe_pattern(const std::string& pattern, ChannelHandler handler);
  static constexpr size_t kMatchedChannels = 1024;

  // Every message delivered to at least one subscription is first shown to `tap` (one call per message, before its
  // handlers; an empty function: none). The controller manager stamps what it takes in with it (cm_inputs_t).
  void set_tap(ChannelHandler tap) { tap_ = std::move(tap); }

  // Handles the datagrams already queued, without blocking, at most `max` and none after the monotonic time
  // `until_us` (the first is always read): how many were read, or -1 on a socket error. No allocation once
  // subscribed.
  int handle_queued(int max = 1000, int64_t until_us = INT64_MAX);

  // In the handler of the message `rb` being delivered: its bytes, to keep. A message put together from fragments in
  // a buffer over kKeptBytes, which has one receiver here, is moved out (its buffer would be given back anyway):
  // taking a 4 MiB goal costs no copy. Any other is copied.
  std::vector<uint8_t> take_delivered(const lcm::ReceiveBuffer& rb);
  // Where a taken message's bytes go back once read (BytePool::give_back, from any thread): the next large message
  // is put together in their room, touching no fresh page on the reading thread.
  const std::shared_ptr<BytePool>& pool() const { return pool_; }

  // Waits up to timeout_ms for a message on `channel`, skipping (not handling) every other datagram: its payload,
  // or nullptr on timeout. For start-up checks and benchmarks, not for a socket with subscribers (its filter admits only theirs).
  const uint8_t* wait_for(std::string_view channel, int timeout_ms, int* size = nullptr);

  static constexpr uint32_t kMaxMessageBytes = 4u << 20;        // a larger message is refused (counted, told)
  static constexpr int64_t kFragmentTimeoutUs = 1'000'000;      // a message in progress unheard this long is dropped
  static constexpr size_t kKeptBytes = 256u << 10;              // reassembly buffers up to this size are kept
  int64_t reassembled() const { return reassembled_; }  // fragmented messages put together and delivered
  int64_t incomplete() const { return incomplete_; }    // fragmented messages given up (a fragment lost or late)
  int64_t too_large() const { return too_large_; }      // fragmented messages refused for their size
  // Bytes held for messages in progress and kept buffers (what fragments cost in memory): a large message's room
  // counts what arrived in it, the pages touched.
  size_t reassembly_bytes() const;
  // Datagrams on the port that are not LCM's (under a filter, a broken whole message naming no channel here is dropped
  // by the kernel, uncounted).
  int64_t not_lcm() const { return not_lcm_; }
  // The channels the kernel's filter admits whole messages on; empty when it admits every datagram.
  const std::vector<std::string>& filtered_to() const { return filter_names_; }
  size_t matched_channels() const { return matched_.size(); }  // names whose pattern matches are remembered

 private:
  // Reads one datagram into buf_ without waiting (*n: recvfrom's result): true when it completes a message.
  bool receive(ssize_t* n, std::string_view* channel, const uint8_t** payload, int* size);
  // The channel and payload of the message the datagram of n bytes in buf_ completes; false when it completes
  // none (a fragment of one still in progress, or not LCM: counted).
  bool parse(int n, const sockaddr_in& from, std::string_view* channel, const uint8_t** payload, int* size);
  bool fragment(int n, const sockaddr_in& from, std::string_view* channel, const uint8_t** payload, int* size);
  bool subscribed(std::string_view channel);
  // Installs the socket filter for the subscriptions as they are now, or removes it when one is a pattern.
  void refilter();
  // The pattern subscriptions (indices into patterns_) that `channel` matches, remembered as above.
  const std::vector<size_t>& matching(std::string_view channel);

  struct Partial {
    bool active = false;
    uint32_t addr = 0;
    uint16_t port = 0;
    uint32_t seqno = 0, total = 0, filled = 0;
    uint16_t count = 0, received = 0;
    bool wanted = false, named = false;
    bool dropped = false;  // given up (counted, told); its remaining fragments are skipped
    std::string channel;
    std::vector<uint8_t> data;  // kept between messages up to kKeptBytes: no allocation once grown
    std::vector<uint8_t> kept;  // that buffer, set aside while `data` is a large message's room
    int64_t heard_us = 0;
  };
  // Gives up the message in progress of `p`, telling its channel's lost handlers.
  void drop(Partial& p);
  // A large message's room in `p` to the pool with `keep` (freed here when the pool is busy), else freed; and its
  // kept buffer back.
  void release_room(Partial& p, bool keep);
  void tell_lost(const Lost& lost);
  // Drops the messages in progress unheard for kFragmentTimeoutUs, and gives back idle buffers over kKeptBytes.
  void expire(int64_t now_us);

  struct Entry {
    int id;
    std::string channel;
    Handler handler;
  };
  std::string url_;
  int fd_ = -1;
  std::vector<Entry> subscribers_;
  ChannelHandler tap_;
  struct LostEntry {
    int id;
    std::string channel;
    LostHandler handler;
  };
  std::vector<LostEntry> lost_handlers_;
  struct PatternEntry {
    int id;
    ChannelPattern pattern;
    ChannelHandler handler;
  };
  std::vector<PatternEntry> patterns_;
  std::unordered_map<std::string, std::vector<size_t>> matched_;  // channel -> patterns_ it matches
  std::string name_;  // the channel being matched or delivered (reused: no allocation once grown)
  std::vector<uint8_t> buf_ = std::vector<uint8_t>(65536);
  Partial partials_[4];
  int64_t reassembled_ = 0, incomplete_ = 0, too_large_ = 0, not_lcm_ = 0;
  std::vector<std::string> filter_names_;
  int64_t arrived_us_ = -1;  // the kernel's arrival stamp of the datagram receive() read last, -1 without one
  Partial* delivering_ = nullptr;  // the put-together message being delivered, while its one receiver may take it
  std::shared_ptr<BytePool> pool_ = std::make_shared<BytePool>();
};

// One line for a lost message: its channel, size and why, with what to do.
std::string describe(const LcmSocket::Lost& lost);

}  // namespace lcm_control
