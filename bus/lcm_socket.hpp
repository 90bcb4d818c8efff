// LCM's udpm datagrams read on the calling thread, for the hardware loop: no LCM receive thread, no pipe and no
// queue between the socket and the handler, so each hop of a lockstep exchange costs one thread wake-up less
// (bench/README.md, "Below the floor"). The packets are LCM's own (lcm::LCM publishes them), so lcm-spy,
// lcm-logger and lcm-logplayer see and replay the same messages.
// A message LCM sends whole ("LC02") is handed over from the receive buffer; one it split into "LC03" fragments
// (over 64 kB with Debian's LCM, over 1,400 bytes with some other builds) is put together first, as LCM does: one
// message in progress per sender, up to kMaxMessageBytes.
#pragma once

#include <lcm/lcm-cpp.hpp>
#include <netinet/in.h>
#include <sys/types.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

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

  // Handles the datagrams already queued, without blocking, at most `max`: how many were read, or -1 on a socket
  // error. No allocation once subscribed.
  int handle_queued(int max = 1000);

  // Waits up to timeout_ms for a message on `channel`, skipping (not handling) every other datagram: its payload,
  // or nullptr on timeout. For start-up checks and benchmarks, not for a socket with subscribers.
  const uint8_t* wait_for(std::string_view channel, int timeout_ms, int* size = nullptr);

  static constexpr uint32_t kMaxMessageBytes = 16u << 20;  // larger fragmented messages are not LCM's (counted)
  int64_t reassembled() const { return reassembled_; }  // fragmented messages put together and delivered
  int64_t incomplete() const { return incomplete_; }    // fragmented messages given up (a fragment lost)
  int64_t not_lcm() const { return not_lcm_; }          // datagrams on the port that are not LCM's

 private:
  // Reads one datagram into buf_ without waiting (*n: recvfrom's result): true when it completes a message.
  bool receive(ssize_t* n, std::string_view* channel, const uint8_t** payload, int* size);
  // The channel and payload of the message the datagram of n bytes in buf_ completes; false when it completes
  // none (a fragment of one still in progress, or not LCM: counted).
  bool parse(int n, const sockaddr_in& from, std::string_view* channel, const uint8_t** payload, int* size);
  bool fragment(int n, const sockaddr_in& from, std::string_view* channel, const uint8_t** payload, int* size);
  bool subscribed(std::string_view channel) const;

  struct Partial {
    bool active = false;
    uint32_t addr = 0;
    uint16_t port = 0;
    uint32_t seqno = 0, total = 0;
    uint16_t count = 0, received = 0;
    bool wanted = true, named = false;
    std::string channel;
    std::vector<uint8_t> data;  // kept between messages: no allocation once grown
    int64_t heard_us = 0;
  };

  struct Entry {
    int id;
    std::string channel;
    Handler handler;
  };
  std::string url_;
  int fd_ = -1;
  std::vector<Entry> subscribers_;
  std::vector<uint8_t> buf_ = std::vector<uint8_t>(65536);
  Partial partials_[4];
  int64_t reassembled_ = 0, incomplete_ = 0, not_lcm_ = 0;
  int64_t arrived_us_ = -1;  // the kernel's arrival stamp of the datagram receive() read last, -1 without one
};

}  // namespace lcm_control
