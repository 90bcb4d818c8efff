#include "common/bus.hpp"

#include <fmt/format.h>

#include <chrono>
#include <cstdlib>

namespace lcm_control {

std::string gains_set_channel(const std::string& owner) { return owner + "/gains/set"; }
std::string gains_channel(const std::string& owner) { return owner + "/gains"; }

Bus::Bus(const std::string& url, const std::string& ns) : ns_(ns) {
  const char* env = std::getenv("LCM_DEFAULT_URL");
  url_ = !url.empty() ? url : (env && *env ? env : "udpm://239.255.76.67:7667?ttl=0");
  while (!ns_.empty() && ns_.back() == '/') ns_.pop_back();
  while (!ns_.empty() && ns_.front() == '/') ns_.erase(0, 1);
  prefix_ = ns_.empty() ? "" : ns_ + "/";
  lcm_ = std::make_unique<lcm::LCM>(url);  // "" lets LCM read LCM_DEFAULT_URL itself
  if (!lcm_->good())
    throw BusError(fmt::format(
        "LCM could not start on '{}': check the URL (--lcm-url or LCM_DEFAULT_URL); for udpm:// on this host, loopback "
        "needs a multicast route: run as root `ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo` "
        "(scripts/setup does this)",
        url_));
}

bool Bus::handle(int timeout_ms) { return lcm_->handleTimeout(timeout_ms) >= 0; }

int64_t monotonic_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now().time_since_epoch())
      .count();
}
int64_t wall_us() {
  return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace lcm_control
