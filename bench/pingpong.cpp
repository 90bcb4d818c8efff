// Round-trip floors: raw UDP and bare LCM ping-pong clients and echo servers (see pingpong.hpp).
#include "bench/pingpong.hpp"

#include "bus/hardware_wire.hpp"
#include "description/robot_model.hpp"
#include "lcm_control/hardware_state_t.hpp"

#include <arpa/inet.h>
#include <linux/futex.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

namespace lcm_control::bench {

hardware_state_t resting_state(const RobotModel& model, int64_t session, bool lockstep) {
  hardware_state_t st{};
  st.session = session;
  st.lockstep = lockstep;
  st.period_us = 1000;
  st.e_stop = false;
  st.real_time_factor = lockstep ? 0 : 1;
  st.num_actuators = int32_t(model.transmissions.size());
  for (const TransmissionSpec& t : model.transmissions) {
    st.name.push_back(t.actuator);
    st.mode.push_back(wire_mode(t.interfaces.front()));
  }
  st.position.assign(st.name.size(), 0.0);
  st.velocity.assign(st.name.size(), 0.0);
  st.effort.assign(st.name.size(), 0.0);
  return st;
}

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

double quantile(std::vector<double> v, double f) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, size_t(f * double(v.size() - 1) + 0.5))];
}

RttSummary summarize(const std::vector<double>& rtt_us, int lost) {
  RttSummary s;
  s.n = int(rtt_us.size());
  s.lost = lost;
  if (rtt_us.empty()) {
    s.min = s.p50 = s.p99 = s.max = std::nan("");
    return s;
  }
  std::vector<double> v = rtt_us;
  std::sort(v.begin(), v.end());
  auto q = [&](double f) { return v[std::min(v.size() - 1, size_t(f * double(v.size() - 1) + 0.5))]; };
  s.min = v.front();
  s.p50 = q(0.5);
  s.p99 = q(0.99);
  s.max = v.back();
  return s;
}

namespace {

int udp_socket(int port) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) throw std::runtime_error("socket() failed");
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(uint16_t(port));
  if (bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
    close(fd);
    throw std::runtime_error("bind() to 127.0.0.1:" + std::to_string(port) + " failed");
  }
  return fd;
}

}  // namespace

UdpPinger::UdpPinger(int port, int ping_bytes, int pong_bytes)
    : fd_(udp_socket(0)),
      ping_bytes_(std::max<int>(ping_bytes, sizeof(int))),
      buf_(size_t(std::max({ping_bytes, pong_bytes, 64}) + 64)),
      out_(size_t(ping_bytes_), 3),
      to_(sizeof(sockaddr_in)) {
  std::memcpy(out_.data(), &pong_bytes, sizeof(int));  // the ping says how big the pong is
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(uint16_t(port));
  std::memcpy(to_.data(), &to, sizeof(to));
}

UdpPinger::~UdpPinger() {
  if (fd_ >= 0) close(fd_);
}

double UdpPinger::round_trip_us(int timeout_ms) {
  const int64_t t0 = now_ns();
  sendto(fd_, out_.data(), out_.size(), 0, reinterpret_cast<const sockaddr*>(to_.data()), sizeof(sockaddr_in));
  pollfd p{fd_, POLLIN, 0};
  if (poll(&p, 1, timeout_ms) <= 0) return -1;
  if (recv(fd_, buf_.data(), buf_.size(), 0) <= 0) return -1;
  return double(now_ns() - t0) / 1e3;
}

LcmPinger::LcmPinger(const std::string& url, int ping_bytes, int pong_bytes)
    : lc_(url), ping_(size_t(std::max<int>(ping_bytes, sizeof(int))), 3) {
  std::memcpy(ping_.data(), &pong_bytes, sizeof(int));
  if (lc_.good()) lc_.subscribe("PONG", &LcmPinger::on_pong, this);
}

bool LcmPinger::wait_for_echo(double timeout_s) {
  const int64_t end = now_ns() + int64_t(timeout_s * 1e9);
  got_ = false;
  while (!got_ && now_ns() < end) {
    lc_.publish("PING", ping_.data(), unsigned(ping_.size()));
    lc_.handleTimeout(20);
  }
  while (lc_.handleTimeout(5) > 0) {  // drain late answers
  }
  return got_;
}

double LcmPinger::round_trip_us(int timeout_ms) {
  got_ = false;
  const int64_t t0 = now_ns();
  lc_.publish("PING", ping_.data(), unsigned(ping_.size()));
  while (!got_)
    if (lc_.handleTimeout(timeout_ms) <= 0) return -1;
  return double(now_ns() - t0) / 1e3;
}

namespace {
// How many bytes the pong to `ping` (n bytes) must have: its first 4 bytes ask, within [4, max]; 0 for a ping too
// short to ask.
int pong_size(const void* ping, size_t n, size_t max) {
  if (n < sizeof(int)) return 0;
  int asked = 0;
  std::memcpy(&asked, ping, sizeof(int));
  return std::clamp<int>(asked, sizeof(int), int(max));
}
}  // namespace

int udp_echo(int port) {
  const int fd = udp_socket(port);
  std::vector<char> buf(65536);
  sockaddr_in from{};
  for (;;) {
    socklen_t len = sizeof(from);
    const ssize_t n = recvfrom(fd, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &len);
    const int pong = n < 0 ? 0 : pong_size(buf.data(), size_t(n), buf.size());
    if (pong > 0) sendto(fd, buf.data(), size_t(pong), 0, reinterpret_cast<sockaddr*>(&from), len);
  }
}

namespace {
struct Echo {
  lcm::LCM* lc;
  std::vector<uint8_t> pong = std::vector<uint8_t>(65536, 7);
  void on(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    if (const int n = pong_size(rbuf->data, rbuf->data_size, pong.size()); n > 0)
      lc->publish("PONG", pong.data(), unsigned(n));
  }
};
}  // namespace

int lcm_echo(const std::string& url) {
  lcm::LCM lc(url);
  if (!lc.good()) {
    std::fprintf(stderr, "bench: LCM cannot start on %s\n", url.c_str());
    return 1;
  }
  Echo e{&lc};
  lc.subscribe("PING", &Echo::on, &e);
  for (;;) lc.handle();
}

LcmDirectPinger::LcmDirectPinger(const std::string& url, int ping_bytes, int pong_bytes)
    : lc_(url), reader_(url), ping_(size_t(std::max<int>(ping_bytes, sizeof(int))), 3) {
  std::memcpy(ping_.data(), &pong_bytes, sizeof(int));
}

bool LcmDirectPinger::wait_for_echo(double timeout_s) {
  const int64_t end = now_ns() + int64_t(timeout_s * 1e9);
  while (now_ns() < end) {
    lc_.publish("PING", ping_.data(), unsigned(ping_.size()));
    if (reader_.wait_for("PONG", 20)) {
      while (reader_.wait_for("PONG", 5)) {  // drain late answers
      }
      return true;
    }
  }
  return false;
}

double LcmDirectPinger::round_trip_us(int timeout_ms) {
  const int64_t t0 = now_ns();
  lc_.publish("PING", ping_.data(), unsigned(ping_.size()));
  if (!reader_.wait_for("PONG", timeout_ms)) return -1;
  return double(now_ns() - t0) / 1e3;
}

int lcm_direct_echo(const std::string& url) {
  lcm::LCM lc(url);
  if (!lc.good()) {
    std::fprintf(stderr, "bench: LCM cannot start on %s\n", url.c_str());
    return 1;
  }
  LcmSocket reader(url);
  std::vector<uint8_t> pong(65536, 7);
  for (;;) {
    int n = 0;
    const uint8_t* ping = reader.wait_for("PING", 1000, &n);
    if (const int size = ping ? pong_size(ping, size_t(n), pong.size()) : 0; size > 0)
      lc.publish("PONG", pong.data(), unsigned(size));
  }
}

FutexPinger::FutexPinger(int ping_bytes, int pong_bytes) : ping_(size_t(ping_bytes), 1), pong_(size_t(pong_bytes), 2) {
  map_ = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (map_ == MAP_FAILED) throw std::runtime_error("mmap failed");
  word_ = new (map_) std::atomic<uint32_t>(0);
  data_ = static_cast<uint8_t*>(map_) + 64;
  child_ = fork();
  if (child_ == 0) echo();
}

FutexPinger::~FutexPinger() {
  word_->store(UINT32_MAX);
  wake();
  waitpid(child_, nullptr, 0);
  munmap(map_, kBytes);
}

double FutexPinger::round_trip_us(int) {
  const auto t0 = std::chrono::steady_clock::now();
  std::memcpy(data_, ping_.data(), ping_.size());
  const uint32_t sent = seq_ + 1;
  word_->store(sent);
  wake();
  wait_for(sent + 1);
  std::memcpy(ping_.data(), data_, pong_.size() < ping_.size() ? pong_.size() : ping_.size());
  seq_ = sent + 1;
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
}

void FutexPinger::wake() {
  syscall(SYS_futex, reinterpret_cast<uint32_t*>(word_), FUTEX_WAKE, INT_MAX, nullptr, nullptr, 0);
}

void FutexPinger::wait_for(uint32_t v) {
  for (uint32_t w = word_->load(); w != v && w != UINT32_MAX; w = word_->load())
    syscall(SYS_futex, reinterpret_cast<uint32_t*>(word_), FUTEX_WAIT, w, nullptr, nullptr, 0);
}

void FutexPinger::echo() {
  std::vector<uint8_t> in(ping_.size());
  for (uint32_t next = 1;; next += 2) {
    wait_for(next);
    if (word_->load() == UINT32_MAX) _exit(0);
    std::memcpy(in.data(), data_, in.size());
    std::memcpy(data_, pong_.data(), pong_.size());
    word_->store(next + 1);
    wake();
  }
}

}  // namespace lcm_control::bench
