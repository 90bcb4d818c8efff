// Round-trip floors for the loop benchmark: a bare LCM ping-pong and a raw UDP
// ping-pong on loopback, same payload sizes as the hardware loop, two processes.
//   bench_pingpong udp-echo PORT            | bench_pingpong udp-ping PORT N WARMUP PING_BYTES PONG_BYTES
//   bench_pingpong lcm-echo URL PONG_BYTES  | bench_pingpong lcm-ping URL N WARMUP PING_BYTES
// The ping side prints "min_us p50_us p99_us max_us lost".
#include <arpa/inet.h>
#include <lcm/lcm-cpp.hpp>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {

int64_t now_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

void report(std::vector<double>& rtt_us, int lost) {
  if (rtt_us.empty()) {
    std::printf("nan nan nan nan %d\n", lost);
    return;
  }
  std::sort(rtt_us.begin(), rtt_us.end());
  auto q = [&](double f) { return rtt_us[std::min(rtt_us.size() - 1, size_t(f * (rtt_us.size() - 1) + 0.5))]; };
  std::printf("%.2f %.2f %.2f %.2f %d\n", rtt_us.front(), q(0.5), q(0.99), rtt_us.back(), lost);
}

int udp_socket(int port) {
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  a.sin_port = htons(port);
  if (bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
    std::perror("bind");
    std::exit(1);
  }
  return fd;
}

int udp_echo(int port) {
  const int fd = udp_socket(port);
  std::vector<char> buf(65536);
  sockaddr_in from{};
  for (;;) {
    socklen_t len = sizeof(from);
    const ssize_t n = recvfrom(fd, buf.data(), buf.size(), 0, reinterpret_cast<sockaddr*>(&from), &len);
    if (n <= 0) continue;
    int pong = 0;
    std::memcpy(&pong, buf.data(), sizeof(int));  // the ping says how big the pong is
    sendto(fd, buf.data(), std::max<int>(pong, sizeof(int)), 0, reinterpret_cast<sockaddr*>(&from), len);
  }
}

int udp_ping(int port, int n, int warmup, int ping_bytes, int pong_bytes) {
  const int fd = udp_socket(0);
  sockaddr_in to{};
  to.sin_family = AF_INET;
  to.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  to.sin_port = htons(port);
  std::vector<char> buf(std::max({ping_bytes, pong_bytes, 64}) + 64);
  std::memcpy(buf.data(), &pong_bytes, sizeof(int));
  std::vector<double> rtt;
  rtt.reserve(n);
  int lost = 0;
  for (int k = 0; k < n + warmup; ++k) {
    const int64_t t0 = now_ns();
    sendto(fd, buf.data(), std::max<int>(ping_bytes, sizeof(int)), 0, reinterpret_cast<sockaddr*>(&to), sizeof(to));
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 1000) <= 0) {
      ++lost;
      continue;
    }
    recv(fd, buf.data(), buf.size(), 0);
    if (k >= warmup) rtt.push_back((now_ns() - t0) / 1e3);
  }
  report(rtt, lost);
  return 0;
}

struct Echo {
  lcm::LCM* lc;
  std::vector<uint8_t> pong;
  void on(const lcm::ReceiveBuffer*, const std::string&) { lc->publish("PONG", pong.data(), pong.size()); }
};

int lcm_echo(const std::string& url, int pong_bytes) {
  lcm::LCM lc(url);
  if (!lc.good()) return 1;
  Echo e{&lc, std::vector<uint8_t>(pong_bytes, 7)};
  lc.subscribe("PING", &Echo::on, &e);
  for (;;) lc.handle();
}

struct Pinger {
  bool got = false;
  void on(const lcm::ReceiveBuffer*, const std::string&) { got = true; }
};

int lcm_ping(const std::string& url, int n, int warmup, int ping_bytes) {
  lcm::LCM lc(url);
  if (!lc.good()) return 1;
  Pinger p;
  lc.subscribe("PONG", &Pinger::on, &p);
  std::vector<uint8_t> ping(ping_bytes, 3);
  std::vector<double> rtt;
  rtt.reserve(n);
  int lost = 0;
  // Wait for the echo process to be subscribed.
  for (int k = 0; k < 200 && !p.got; ++k) {
    lc.publish("PING", ping.data(), ping.size());
    lc.handleTimeout(20);
  }
  while (lc.handleTimeout(5) > 0) {
  }
  for (int k = 0; k < n + warmup; ++k) {
    p.got = false;
    const int64_t t0 = now_ns();
    lc.publish("PING", ping.data(), ping.size());
    while (!p.got)
      if (lc.handleTimeout(1000) <= 0) break;
    if (!p.got) {
      ++lost;
      continue;
    }
    if (k >= warmup) rtt.push_back((now_ns() - t0) / 1e3);
  }
  report(rtt, lost);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  auto arg = [&](int k) { return k < argc ? std::atoi(argv[k]) : 0; };
  if (mode == "udp-echo" && argc == 3) return udp_echo(arg(2));
  if (mode == "udp-ping" && argc == 7) return udp_ping(arg(2), arg(3), arg(4), arg(5), arg(6));
  if (mode == "lcm-echo" && argc == 4) return lcm_echo(argv[2], arg(3));
  if (mode == "lcm-ping" && argc == 6) return lcm_ping(argv[2], arg(3), arg(4), arg(5));
  std::fprintf(stderr,
               "usage: bench_pingpong udp-echo PORT | udp-ping PORT N WARMUP PING_BYTES PONG_BYTES |\n"
               "       lcm-echo URL PONG_BYTES | lcm-ping URL N WARMUP PING_BYTES\n");
  return 2;
}
