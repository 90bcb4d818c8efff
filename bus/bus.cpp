#include "bus/bus.hpp"

#include <fmt/format.h>

#include <poll.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <ctime>

#include "rt/log.hpp"

namespace lcm_control {

std::string gains_set_channel(const std::string& owner) { return owner + "/gains/set"; }
std::string gains_channel(const std::string& owner) { return owner + "/gains"; }

namespace {
std::string trim_slashes(std::string ns) {
  while (!ns.empty() && ns.back() == '/') ns.pop_back();
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  return ns;
}

std::unique_ptr<lcm::LCM> open_lcm(const std::string& url, const std::string& shown, const char* flag) {
  auto lc = std::make_unique<lcm::LCM>(url);  // "" lets LCM read LCM_DEFAULT_URL itself
  if (!lc->good())
    throw BusError(fmt::format(
        "LCM could not start on '{}': check the URL ({}); for udpm:// on this host, loopback needs a multicast "
        "route: run as root `ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo` (scripts/setup does this)",
        shown, flag));
  return lc;
}
}  // namespace

std::string effective_url(const std::string& url) {
  const char* env = std::getenv("LCM_DEFAULT_URL");
  return !url.empty() ? url : (env && *env ? env : "udpm://239.255.76.67:7667?ttl=0");
}

std::string hardware_url_for(const std::string& value, const std::string& shared_url, const std::string& ns) {
  if (value.empty() || value == "shared") return shared_url;
  if (is_shm_url(value)) return "shm:" + shm_name_of(value, trim_slashes(ns));
  if (value != "auto") return value;
  // udpm://GROUP[:PORT][?OPTIONS]
  const std::string scheme = "udpm://";
  if (shared_url.rfind(scheme, 0) != 0)
    throw BusError(fmt::format("--hardware-url auto derives a port from the shared bus's udpm:// URL, and that "
                               "is '{}': give the hardware loop's URL itself",
                               shared_url));
  const size_t query = shared_url.find('?');
  const std::string host_port = shared_url.substr(scheme.size(), query == std::string::npos ? std::string::npos
                                                                                            : query - scheme.size());
  const std::string options = query == std::string::npos ? "" : shared_url.substr(query);
  const std::string group = host_port.substr(0, host_port.find(':'));
  uint32_t h = 2166136261u;  // FNV-1a: the same namespace gives the same port on every host
  for (const char c : trim_slashes(ns)) h = (h ^ uint8_t(c)) * 16777619u;
  return fmt::format("{}{}:{}{}", scheme, group.empty() ? "239.255.76.67" : group,
                     kHardwarePortBase + int(h % kHardwarePorts), options);
}

HardwareReader hardware_reader_named(const std::string& name) {
  if (name == "direct") return HardwareReader::Direct;
  if (name == "lcm") return HardwareReader::Lcm;
  throw BusError(fmt::format("--hardware-reader '{}': expected direct or lcm", name));
}

namespace {
// The direct reader's start-up check, as LCM's own self-test: a datagram published on the URL must come back.
void self_test(lcm::LCM& publisher, LcmSocket& socket) {
  const char* channel = "LCM_SELF_TEST";
  const std::string text = "lcm_control hardware reader self-test";
  for (int attempt = 0; attempt < 4; ++attempt) {
    publisher.publish(channel, text.data(), unsigned(text.size()));
    if (socket.wait_for(channel, 50)) return;
  }
  throw BusError(fmt::format(
      "{} is read on a socket of this program's own, and its test datagram did not come back within 0.2 s: for "
      "udpm:// on this host, loopback needs a multicast route: run as root `ip link set lo multicast on; ip route add "
      "224.0.0.0/4 dev lo` (scripts/setup does this); a firewall may also drop it (docs/security.md); sim_server and "
      "controller_manager also take --hardware-reader lcm",
      socket.url()));
}
}  // namespace

Bus::Bus(const std::string& url, const std::string& ns, const std::string& hardware_url, HardwareReader reader)
    : url_(effective_url(url)), ns_(trim_slashes(ns)) {
  prefix_ = ns_.empty() ? "" : ns_ + "/";
  lcm_ = open_lcm(url, url_, "--lcm-url or LCM_DEFAULT_URL");
  const std::string hw = hardware_url_for(hardware_url, url_, ns_);
  if (is_shm_url(hw)) {
    hw_url_ = hw;
    shm_ = std::make_unique<ShmLink>(shm_name_of(hw, ns_));
  } else if (hw != url_) {
    hw_url_ = hw;
    hw_ = open_lcm(hw, hw, "--hardware-url");
  }
  const auto udpm = [](const std::string& u) { return u.rfind("udpm://", 0) == 0; };
  if (reader == HardwareReader::Direct && hw_ && udpm(hw_url_)) {
    hw_socket_ = std::make_unique<LcmSocket>(hw_url_);
    self_test(*hw_, *hw_socket_);
  }
  if (reader == HardwareReader::Direct && udpm(url_)) {
    shared_socket_ = std::make_unique<LcmSocket>(url_);
    self_test(*lcm_, *shared_socket_);
  }
  if (shm_) shm_->watch_fd(shared_fd());  // one wait covers the shared bus and the shared memory
}

Bus::~Bus() = default;

void Bus::mirror_hardware(double hz) {
  if (hz > 0 && !shm_)
    throw BusError(fmt::format("--hardware-mirror {:g}: the hardware loop is on LCM ({}), where every tool hears it "
                               "already; the mirror is for --hardware-url shm",
                               hz, hardware_url()));
  if (shm_) shm_->mirror_to(lcm_.get(), hz);
}

std::string Bus::hardware_loss_note() {
  std::string note = shm_ ? shm_->take_tampering_note() : "";
  if (const int64_t skipped = hardware_skipped(); skipped != skipped_noted_) {
    note += fmt::format("{}skipped {} message(s) in {} whose size is past its {} MiB slot ({} so far): a program other "
                       "than sim_server and controller_manager writes that file; stop it, or give this robot another "
                       "--hardware-url shm:NAME",
                       note.empty() ? "" : "; ", skipped - skipped_noted_, shm_->path(), ShmLink::kSlotBytes >> 20, skipped);
    skipped_noted_ = skipped;
  }
  if (const int64_t refused = hardware_refused(); refused != refused_noted_) {
    note += fmt::format("{}could not send {} message(s) through {}: over its {} MiB slot ({} so far); this robot's "
                        "hardware loop is too large for shared memory, give it an LCM --hardware-url",
                        note.empty() ? "" : "; ", refused - refused_noted_, shm_->path(), ShmLink::kSlotBytes >> 20,
                        refused);
    refused_noted_ = refused;
  }
  return note;
}

int Bus::subscribe(const std::string& pattern, ChannelHandler handler, On on, int queue) {
  static std::atomic<int> next_id{1};
  auto s = std::make_unique<Subscription>();
  s->id = next_id++;
  s->handler = std::move(handler);
  s->socket = on == On::Shared ? shared_socket() : hardware_socket();
  s->shm = on == On::Hardware ? shm_.get() : nullptr;
  if (s->shm) {
    s->socket_id = s->shm->subscribe_pattern(pattern, s->handler);
  } else if (s->socket) {
    s->socket_id = s->socket->subscribe_pattern(pattern, s->handler);
  } else {
    s->lc = on == On::Shared ? &lcm() : &hardware();
    s->lcm_sub = s->lc->subscribe(pattern, &Subscription::on, s.get());
    if (!s->lcm_sub)
      throw BusError(fmt::format("cannot subscribe to '{}' on {}: LCM refused it (not a regular expression?)",
                                 clip(pattern), on == On::Shared ? url_ : hardware_url()));
    s->lcm_sub->setQueueCapacity(queue);
  }
  subscriptions_.push_back(std::move(s));
  return subscriptions_.back()->id;
}

void Bus::unsubscribe(int id) {
  for (auto it = subscriptions_.begin(); it != subscriptions_.end(); ++it) {
    if ((*it)->id != id) continue;
    if ((*it)->shm) (*it)->shm->unsubscribe((*it)->socket_id);
    if ((*it)->socket) (*it)->socket->unsubscribe((*it)->socket_id);
    if ((*it)->lcm_sub) (*it)->lc->unsubscribe((*it)->lcm_sub);
    subscriptions_.erase(it);
    return;
  }
}

// lcm::LCM's getFileno() on udpm:// starts its receive thread: only for an instance that is read through LCM.
int Bus::shared_fd() { return shared_socket_ ? shared_socket_->fd() : lcm_->getFileno(); }
int Bus::hardware_fd() { return !hw_ ? -1 : hw_socket_ ? hw_socket_->fd() : hw_->getFileno(); }

std::vector<int> Bus::fds() {
  std::vector<int> v{shared_fd()};
  if (hw_) v.push_back(hardware_fd());
  return v;
}

namespace {
int handle_queued(lcm::LCM& lc, LcmSocket* socket, int max, int64_t budget_us = 0) {
  if (socket) return socket->handle_queued(max, budget_us > 0 ? monotonic_us() + budget_us : INT64_MAX);
  int handled = 0;
  for (; handled < max; ++handled) {
    const int n = lc.handleTimeout(0);
    if (n < 0) return -1;
    if (n == 0) break;
  }
  return handled;
}
}  // namespace

int Bus::handle_shared(int max) {
  const int n = handle_queued(*lcm_, shared_socket_.get(), max, pass_budget_us_);
  if (shm_ && n < max) shm_->fd_drained();  // all read: its watcher looks again
  return n;
}

int Bus::handle_hardware(int max) {
  if (shm_) return shm_->handle_queued(max);
  return hw_ ? handle_queued(*hw_, hw_socket_.get(), max) : handle_shared(max);
}

int Bus::wait_us(int64_t timeout_us) {
  timeout_us = std::max<int64_t>(0, timeout_us);
  if (shm_) return ready(shm_->wait_us(timeout_us));
  pollfd p[2] = {{shared_fd(), POLLIN, 0}, {hardware_fd(), POLLIN, 0}};
  const timespec ts{static_cast<time_t>(timeout_us / 1000000), static_cast<long>(timeout_us % 1000000) * 1000};
  const int r = ppoll(p, hw_ ? 2 : 1, &ts, nullptr);
  if (r < 0) return errno == EINTR ? 0 : -1;
  return ((p[0].revents & POLLIN) ? kSharedReady : 0) | (hw_ && (p[1].revents & POLLIN) ? kHardwareReady : 0);
}

int Bus::wait_until_us(int64_t deadline_us) {
  if (shm_) return ready(shm_->wait_until_us(deadline_us));
  return wait_us(deadline_us - monotonic_us());
}

int Bus::ready(bool woken) {
  if (!woken) return 0;
  return (shm_->has_new() ? kHardwareReady : 0) | (shm_->fd_ready() ? kSharedReady : 0);
}

bool Bus::handle_us(int64_t timeout_us, int max) {
  timeout_us = std::max<int64_t>(0, timeout_us);
  if (!hw_ && !shm_ && !shared_socket_) {
    const int r = lcm_->handleTimeout(static_cast<int>((timeout_us + 999) / 1000));
    return r >= 0 && (r == 0 || handle_shared(max - 1) >= 0);
  }
  const int ready = wait_us(timeout_us);
  if (ready < 0) return false;
  if ((ready & kHardwareReady) && handle_hardware(max) < 0) return false;
  if ((ready & kSharedReady) && handle_shared(max) < 0) return false;
  return true;
}

}  // namespace lcm_control
