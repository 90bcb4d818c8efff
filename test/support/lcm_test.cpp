#include "test/support/lcm_test.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <random>
#include <limits>
#include <stdexcept>

#include "bus/lcm_socket.hpp"

namespace lcm_control::testing {

RawSender::RawSender(const std::string& url) : fd_(socket(AF_INET, SOCK_DGRAM, 0)), to_(sizeof(sockaddr_in)) {
  const UdpmAddress a = parse_udpm_url(url);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_port = htons(uint16_t(a.port));
  inet_pton(AF_INET, a.group.c_str(), &to.sin_addr);
  std::memcpy(to_.data(), &to, sizeof to);
  const unsigned char ttl = 0;
  setsockopt(fd_, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof(ttl));
}

RawSender::~RawSender() { close(fd_); }

void RawSender::send(const std::vector<uint8_t>& d) {
  const ssize_t n = sendto(fd_, d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(to_.data()), socklen_t(to_.size()));
  if (n != ssize_t(d.size())) throw std::runtime_error("RawSender: sendto failed");
}

std::vector<uint8_t> lcm_fragment(uint32_t seqno, uint32_t total, uint32_t offset, uint16_t number, uint16_t count,
                                  const std::vector<uint8_t>& data) {
  std::vector<uint8_t> d{0x4c, 0x43, 0x30, 0x33};
  auto be = [&](uint64_t v, int bytes) {
    for (int k = bytes - 1; k >= 0; --k) d.push_back(uint8_t(v >> (8 * k)));
  };
  be(seqno, 4), be(total, 4), be(offset, 4), be(number, 2), be(count, 2);
  d.insert(d.end(), data.begin(), data.end());
  return d;
}

std::vector<uint8_t> named_payload(const std::string& channel, size_t payload_bytes) {
  std::vector<uint8_t> d(channel.begin(), channel.end());
  d.push_back(0);
  d.resize(d.size() + payload_bytes, 7);
  return d;
}

std::string unique_lcm_url() {
  // A random port below the kernel's ephemeral range: a port from that range can be taken, between this check and
  // LCM's bind, by any socket a sendto binds on its own (every LCM publisher's is one), and LCM's bind then fails
  // with "Address already in use". Checked free with an exclusive bind, which fails where any socket has the port
  // (LCM's, bound with SO_REUSEADDR, too). Per-port isolation is what separates tests (a different multicast group
  // on the same port would leak). Ports below 10000 are left to LCM's default (7667) and hardware URLs (7700-9699).
  int ephemeral_low = 32768;
  std::ifstream("/proc/sys/net/ipv4/ip_local_port_range") >> ephemeral_low;
  if (ephemeral_low <= 11000) throw std::runtime_error("the ephemeral port range starts below 11000: no port to pick");
  std::mt19937 rng(std::random_device{}());
  std::uniform_int_distribution<int> pick(10000, ephemeral_low - 1);
  for (int tries = 0; tries < 1000; ++tries) {
    const int port = pick(rng);
    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd < 0) throw std::runtime_error("socket() failed");
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_ANY);
    a.sin_port = htons(static_cast<uint16_t>(port));
    const bool free = bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) == 0;
    close(fd);
    // A large receive buffer: a lockstep loop on the same port floods every socket.
    if (free) return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
  }
  throw std::runtime_error("no free UDP port below the ephemeral range in 1000 tries");
}

bool pump_until(lcm::LCM& lc, const std::function<bool()>& pred, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (!pred()) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
    if (left.count() <= 0) return pred();
    lc.handleTimeout(static_cast<int>(std::min<int64_t>(left.count(), 50)));
  }
  return true;
}

double sender_clock_drift_s(const std::vector<int64_t>& sender_us, const std::vector<int64_t>& arrival_us,
                            double window_s) {
  const size_t n = std::min(sender_us.size(), arrival_us.size());
  if (n < 2) return 0.0;
  const auto window = static_cast<int64_t>(window_s * 1e6);
  int64_t first = std::numeric_limits<int64_t>::max(), last = std::numeric_limits<int64_t>::max();
  for (size_t k = 0; k < n; ++k) {
    const int64_t late = arrival_us[k] - sender_us[k];
    if (sender_us[k] - sender_us.front() <= window) first = std::min(first, late);
    if (sender_us.back() - sender_us[k] <= window) last = std::min(last, late);
  }
  return double(first - last) * 1e-6;
}

}  // namespace lcm_control::testing
