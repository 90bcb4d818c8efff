// LCM for tests: a URL of its own for every test (a free UDP port on the
// loopback multicast route), and helpers to wait for messages with a deadline.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

namespace lcm_control::testing {

// "udpm://239.255.76.67:PORT?ttl=0&recv_buf_size=4194304" with a port no other running test uses. Under lockstep
// the bus carries thousands of messages per second and every udpm socket on the port receives all of them, whatever
// it subscribes to: a receive buffer of 4 MB (net.core.rmem_max here) keeps a busy process (a JVM, a plotter running
// gnuplot) from dropping any.
std::string unique_lcm_url();

// A UDP socket that sends hand-made datagrams to a udpm:// URL's group and port: one LCM sender, as reassembly tells
// senders apart (ttl 0, nothing leaves the host).
class RawSender {
 public:
  explicit RawSender(const std::string& url);
  ~RawSender();
  RawSender(const RawSender&) = delete;
  RawSender& operator=(const RawSender&) = delete;
  void send(const std::vector<uint8_t>& datagram);
  template <size_t N>
  void send(const uint8_t (&bytes)[N]) {
    send(std::vector<uint8_t>(bytes, bytes + N));
  }

 private:
  int fd_;
  std::vector<uint8_t> to_;  // the sockaddr_in
};

// An LCM fragment ("LC03") as LCM sends it: fragment `number` of `count` of message `seqno` (`total` bytes), at
// `offset`, carrying `data` (fragment 0 starts with the channel name and its NUL; see named_payload).
std::vector<uint8_t> lcm_fragment(uint32_t seqno, uint32_t total, uint32_t offset, uint16_t number, uint16_t count,
                                  const std::vector<uint8_t>& data);
// `channel`, its NUL and payload_bytes filler bytes: the data of a fragment 0.
std::vector<uint8_t> named_payload(const std::string& channel, size_t payload_bytes);

// Pumps lc until pred() is true or timeout_s passes; returns pred().
bool pump_until(lcm::LCM& lc, const std::function<bool()>& pred, double timeout_s);

// How far a sender's clock ran ahead of the arrival clock between the start and the end of a recording,
// in seconds (negative: it fell behind). Each end takes the earliest arrival relative to its stamp within
// window_s of that end, so a receiver that got to its first messages late does not count as drift.
double sender_clock_drift_s(const std::vector<int64_t>& sender_us, const std::vector<int64_t>& arrival_us,
                            double window_s);

// Collects every message of type Msg on one channel.
template <class Msg>
class Recorder {
 public:
  Recorder(lcm::LCM& lc, const std::string& channel) {
    sub_ = lc.subscribe(channel, &Recorder::on, this);
    sub_->setQueueCapacity(0);
  }
  std::vector<Msg> messages;
  std::vector<int64_t> receive_us;  // monotonic times when handled
  std::vector<int64_t> arrival_us;  // wall-clock times LCM's receive thread read them (recv_utime)

 private:
  void on(const lcm::ReceiveBuffer* rb, const std::string&, const Msg* m) {
    messages.push_back(*m);
    arrival_us.push_back(rb->recv_utime);
    receive_us.push_back(std::chrono::duration_cast<std::chrono::microseconds>(
                             std::chrono::steady_clock::now().time_since_epoch())
                             .count());
  }
  lcm::Subscription* sub_ = nullptr;
};

}  // namespace lcm_control::testing
