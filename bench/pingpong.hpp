// Round-trip floors for the loop benchmark, shared by bench_pingpong, bench_loop
// and bench_physics: a raw UDP ping-pong on loopback and a bare LCM ping-pong
// (raw bytes on PING, answered on PONG), with echo servers that answer with as
// many bytes as the first 4 bytes of the ping ask for; a bare futex ping-pong.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include "bus/lcm_socket.hpp"

#include <sys/types.h>

#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace lcm_control {
struct RobotModel;
class hardware_state_t;
}  // namespace lcm_control

namespace lcm_control::bench {

int64_t now_ns();

// What a hardware of `model` publishes at rest: its actuators in transmission order, each in its first interface's
// mode, at 0; step 0, 1 ms period, not e-stopped.
hardware_state_t resting_state(const RobotModel& model, int64_t session, bool lockstep);

// Sorted-copy quantile (nearest rank), NaN for an empty set.
double quantile(std::vector<double> v, double f);

struct RttSummary {
  double min = 0, p50 = 0, p99 = 0, max = 0;
  int n = 0, lost = 0;
};
RttSummary summarize(const std::vector<double>& rtt_us, int lost);

// n timed round trips after `warmup` untimed ones; Pinger::round_trip_us() < 0 means lost.
template <class Pinger>
RttSummary measure(Pinger& p, int n, int warmup) {
  std::vector<double> rtt;
  rtt.reserve(size_t(n));
  int lost = 0;
  for (int k = 0; k < n + warmup; ++k) {
    const double us = p.round_trip_us();
    if (us < 0)
      ++lost;
    else if (k >= warmup)
      rtt.push_back(us);
  }
  return summarize(rtt, lost);
}

// Blocking UDP on 127.0.0.1 against `udp_echo(port)`.
class UdpPinger {
 public:
  UdpPinger(int port, int ping_bytes, int pong_bytes);
  ~UdpPinger();
  UdpPinger(const UdpPinger&) = delete;
  UdpPinger& operator=(const UdpPinger&) = delete;
  // One round trip in microseconds; negative if no answer within timeout_ms.
  double round_trip_us(int timeout_ms = 1000);

 private:
  int fd_ = -1;
  int ping_bytes_;
  std::vector<char> buf_;
  std::vector<char> out_;
  std::vector<unsigned char> to_;  // sockaddr_in
};

// Bare LCM against `lcm_echo(url)`: nothing but publish and handle.
class LcmPinger {
 public:
  LcmPinger(const std::string& url, int ping_bytes, int pong_bytes);
  bool good() const { return lc_.good(); }
  // Pings until the echo answers (it may still be subscribing); false on timeout.
  bool wait_for_echo(double timeout_s);
  double round_trip_us(int timeout_ms = 1000);

 private:
  void on_pong(const lcm::ReceiveBuffer*, const std::string&) { got_ = true; }
  lcm::LCM lc_;
  std::vector<uint8_t> ping_;
  bool got_ = false;
};

// LCM's wire format without LCM's receive thread: publishes with lcm::LCM (which opens no receive socket while
// nothing is subscribed) and reads the group's datagrams on the calling thread (common/lcm_socket, the loops'
// --hardware-reader direct).
class LcmDirectPinger {
 public:
  LcmDirectPinger(const std::string& url, int ping_bytes, int pong_bytes);
  bool good() const { return lc_.good(); }
  bool wait_for_echo(double timeout_s);
  double round_trip_us(int timeout_ms = 1000);

 private:
  lcm::LCM lc_;
  LcmSocket reader_;
  std::vector<uint8_t> ping_;
};

// The bare futex ping-pong between two processes: the ping copies PING_BYTES into shared memory, bumps the word and
// wakes; the echo (forked here) copies them out, PONG_BYTES back, bumps and wakes. What ShmLink's round trip is
// measured against.
class FutexPinger {
 public:
  FutexPinger(int ping_bytes, int pong_bytes);
  ~FutexPinger();
  FutexPinger(const FutexPinger&) = delete;
  FutexPinger& operator=(const FutexPinger&) = delete;
  double round_trip_us(int = 1000);

 private:
  static constexpr size_t kBytes = 1 << 20;
  void wake();
  void wait_for(uint32_t v);
  [[noreturn]] void echo();
  std::vector<uint8_t> ping_, pong_;
  void* map_ = nullptr;
  std::atomic<uint32_t>* word_ = nullptr;
  uint8_t* data_ = nullptr;
  uint32_t seq_ = 0;
  pid_t child_ = -1;
};

// Echo servers; they run until killed.
int udp_echo(int port);
int lcm_echo(const std::string& url);
int lcm_direct_echo(const std::string& url);

}  // namespace lcm_control::bench
