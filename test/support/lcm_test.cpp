#include "test/support/lcm_test.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace lcm_control::testing {

std::string unique_lcm_url() {
  // The kernel hands out a UDP port nobody has bound; LCM then binds the same
  // port with SO_REUSEADDR. Per-port isolation is what separates tests (a
  // different multicast group on the same port would leak).
  const int fd = socket(AF_INET, SOCK_DGRAM, 0);
  if (fd < 0) throw std::runtime_error("socket() failed");
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_ANY);
  a.sin_port = 0;
  socklen_t len = sizeof(a);
  if (bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0 ||
      getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len) != 0) {
    close(fd);
    throw std::runtime_error("bind() failed");
  }
  const int port = ntohs(a.sin_port);
  close(fd);
  // A large receive buffer: a lockstep loop on the same port floods every socket.
  return "udpm://239.255.76.67:" + std::to_string(port) + "?ttl=0&recv_buf_size=4194304";
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
