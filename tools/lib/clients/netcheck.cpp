#include "tools/lib/clients/netcheck.hpp"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <sys/socket.h>
#include <unistd.h>

#include <fmt/format.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <utility>

#include "lcm_control/netcheck_t.hpp"
#include "tools/lib/process/process.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {
namespace {

constexpr const char* kChannel = "lcm_control/netcheck";

// "eth0=192.168.1.5 lo=127.0.0.1".
std::string addresses() {
  ifaddrs* list = nullptr;
  if (getifaddrs(&list) != 0) return "";
  std::string out;
  for (ifaddrs* i = list; i; i = i->ifa_next) {
    if (!i->ifa_addr || i->ifa_addr->sa_family != AF_INET) continue;
    char text[INET_ADDRSTRLEN] = {};
    inet_ntop(AF_INET, &reinterpret_cast<sockaddr_in*>(i->ifa_addr)->sin_addr, text, sizeof text);
    out += fmt::format("{}{}={}", out.empty() ? "" : " ", i->ifa_name, text);
  }
  freeifaddrs(list);
  return out;
}

// The interface multicast to the group leaves by, from the kernel's route (`ip route get`: the source address
// alone does not tell it), or why there is none.
std::string route_line(const UdpmAddress& u) {
  std::string out;
  const int rc = run_and_wait({"ip", "route", "get", u.group}, 3.0, &out);
  const size_t at = out.find(" dev ");
  if (rc != 0 || at == std::string::npos)
    return fmt::format("no route for multicast to {} ({}): as root, `ip route add 224.0.0.0/4 dev IF` with IF the "
                       "network the other computers are on (lo for this computer only)",
                       u.group, out.empty() ? "ip route get failed" : out.substr(0, out.find('\n')));
  const std::string dev = out.substr(at + 5, out.find_first_of(" \n", at + 5) - (at + 5));
  std::string line = fmt::format("multicast to {} leaves by {}", u.group, dev);
  if (dev == "lo" && u.ttl > 0)
    line += ": only this computer hears it. To reach the others, route multicast to their network instead (as "
            "root: `ip route replace 224.0.0.0/4 dev IF`)";
  return line;
}

struct Peer {
  std::string addresses;
  bool heard = false, answered = false;  // its probe reached us; it answered ours
};

// Answers every probe it hears (a lost answer is made good by the next one), and keeps who was heard.
class Prober {
 public:
  Prober(Bus& bus, netcheck_t self) : bus_(bus), self_(std::move(self)) {
    sub_ = subscribe_guarded<&Prober::on>(bus_, kChannel, this);
  }
  ~Prober() { bus_.unsubscribe(sub_); }
  void probe() {
    self_.utime = wall_us();
    bus_.lcm().publish(kChannel, &self_);
  }
  const std::map<std::pair<std::string, int32_t>, Peer>& peers() const { return peers_; }

 private:
  void on(const lcm::ReceiveBuffer*, const std::string&, const netcheck_t* m) {
    if (m->host == self_.host && m->pid == self_.pid) return;
    if (m->answer && (m->to_host != self_.host || m->to_pid != self_.pid)) return;  // an answer to someone else
    Peer& p = peers_[{m->host, m->pid}];
    if (!p.heard && !p.answered) {
      fmt::print("peer:      {} pid {}: {}\n", m->host, m->pid, m->addresses);
      std::fflush(stdout);
    }
    p.addresses = m->addresses;
    if (m->answer) {
      p.answered = true;
      return;
    }
    p.heard = true;
    netcheck_t a = self_;
    a.utime = wall_us();
    a.answer = true;
    a.to_host = m->host;
    a.to_pid = m->pid;
    bus_.lcm().publish(kChannel, &a);
  }
  Bus& bus_;
  netcheck_t self_;
  int sub_ = 0;
  std::map<std::pair<std::string, int32_t>, Peer> peers_;
};

}  // namespace

int cmd_netcheck(Bus& bus, double duration_s, bool answer_only) {
  const UdpmAddress url = parse_udpm_url(bus.url());
  char name[256] = {};
  gethostname(name, sizeof name - 1);
  const std::string host = name;
  const int32_t pid = int32_t(getpid());
  fmt::print("url:       {} (group {}, port {}, ttl {})\n", bus.url(), url.group, url.port, url.ttl);
  if (url.ttl == 0)
    fmt::print("ttl:       0: nothing leaves this computer (the default). For a robot on several computers give every "
               "program --lcm-url 'udpm://{}:{}?ttl=1' (or set LCM_DEFAULT_URL)\n",
               url.group, url.port);
  fmt::print("route:     {}\n", route_line(url));
  std::string nft_out;
  if (run_and_wait({"nft", "list", "table", "inet", "lcm_control"}, 3.0, &nft_out) == 0)
    fmt::print("firewall:  nftables table inet lcm_control is installed (scripts/lcm-firewall): UDP to its ports is "
               "taken only from this computer and the interfaces and peers it allows; allow the robot's other "
               "computers with scripts/lcm-firewall install --port {} --allow-from ADDR (or --allow-interface IF)\n",
               url.port);
  netcheck_t self{};
  self.host = host;
  self.pid = pid;
  self.addresses = addresses();
  fmt::print("host:      {} pid {}: {}\n", host, pid, self.addresses);
  std::fflush(stdout);  // line by line, for whoever watches it run

  Prober prober(bus, self);
  const int64_t start = monotonic_us();
  int64_t next_probe = start;
  while (!stop_requested() && (duration_s <= 0 || monotonic_us() - start < int64_t(duration_s * 1e6))) {
    if (!answer_only && monotonic_us() >= next_probe) {
      prober.probe();
      next_probe += 500000;
    }
    bus.handle(50, 100);
  }
  int both = 0;
  for (const auto& [who, p] : prober.peers()) {
    fmt::print("result:    {} pid {}: {}\n", who.first, who.second,
               p.answered ? "answered our probe (both ways work)"
                          : answer_only ? "its probe reached us (we answered)"
                                        : "its probe reached us, but it did not answer ours (one way only: check the "
                                          "other computer's route and firewall)");
    both += p.answered || answer_only;
  }
  if (both > 0) return 0;
  throw BusError(fmt::format(
      "no other netcheck answered on {} within {}: run `bus netcheck` on the other computers at the same time (or "
      "`bus netcheck --answer` there), with the same --lcm-url{}",
      bus.url(), seconds_text(duration_s), url.ttl == 0 ? "; with ttl=0 only programs on this computer can answer" : ""));
}

}  // namespace lcm_control::tools
