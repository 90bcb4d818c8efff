#include "bus/lcm_socket.hpp"

#include <arpa/inet.h>
#include <fmt/format.h>
#include <linux/filter.h>
#include <netinet/in.h>
#include <poll.h>
#include <regex.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/uio.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <set>

#include "bus/bus_error.hpp"
#include "rt/clock.hpp"
#include "bus/wire_check.hpp"
#include "rt/log.hpp"

namespace lcm_control {

namespace {
constexpr uint8_t kShort[4] = {0x4c, 0x43, 0x30, 0x32};     // "LC02": a whole message
constexpr uint8_t kFragment[4] = {0x4c, 0x43, 0x30, 0x33};  // "LC03": one fragment of a longer one
constexpr int kShortHeader = 8;                              // magic, sequence number
constexpr int kFragmentHeader = 20;  // magic, sequence number, size, offset, fragment number (u16), fragments (u16)

int read_int(const std::string& url, const std::string& text, const char* what) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || *end != '\0' || errno != 0 || v < 0 || v > (1L << 30))
    throw BusError(fmt::format("LCM URL '{}': {} '{}' is not a number", url, what, text));
  return int(v);
}
}  // namespace

UdpmAddress parse_udpm_url(const std::string& url) {
  const std::string scheme = "udpm://";
  if (url.rfind(scheme, 0) != 0)
    throw BusError(fmt::format("'{}' is not a udpm:// URL (udpm://GROUP:PORT?ttl=N, LCM's UDP multicast)", url));
  UdpmAddress a;
  const size_t q = url.find('?');
  const std::string host_port = url.substr(scheme.size(), q == std::string::npos ? q : q - scheme.size());
  const size_t colon = host_port.find(':');
  if (!host_port.substr(0, colon).empty()) a.group = host_port.substr(0, colon);
  if (colon != std::string::npos) a.port = read_int(url, host_port.substr(colon + 1), "port");
  if (a.port <= 0 || a.port > 65535) throw BusError(fmt::format("LCM URL '{}': port {} is out of range", url, a.port));
  in_addr group{};
  if (inet_pton(AF_INET, a.group.c_str(), &group) != 1 || !IN_MULTICAST(ntohl(group.s_addr)))
    throw BusError(fmt::format("LCM URL '{}': '{}' is not an IPv4 multicast group (224.0.0.0 to 239.255.255.255)",
                               url, a.group));
  if (q == std::string::npos) return a;
  std::string options = url.substr(q + 1);
  for (size_t start = 0; start <= options.size();) {
    const size_t amp = std::min(options.find('&', start), options.size());
    const std::string kv = options.substr(start, amp - start);
    start = amp + 1;
    const size_t eq = kv.find('=');
    const std::string key = kv.substr(0, eq), value = eq == std::string::npos ? "" : kv.substr(eq + 1);
    if (key == "recv_buf_size") a.recv_buf_size = read_int(url, value, "recv_buf_size");
    if (key == "ttl") a.ttl = read_int(url, value, "ttl");
  }
  return a;
}

LcmSocket::LcmSocket(const std::string& url) : url_(url) {
  const UdpmAddress a = parse_udpm_url(url);
  fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) throw BusError(fmt::format("cannot open a UDP socket for {}: {}", url, std::strerror(errno)));
  auto fail = [&](const char* what) {
    const std::string why = std::strerror(errno);
    close(fd_);
    fd_ = -1;
    throw BusError(fmt::format(
        "cannot read {} directly ({} failed: {}): for udpm:// on this host, loopback needs a multicast route: run as "
        "root `ip link set lo multicast on; ip route add 224.0.0.0/4 dev lo` (scripts/setup does this), or give "
        "--hardware-reader lcm",
        url, what, why));
  };
  const int one = 1;
  if (setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one)) != 0) fail("SO_REUSEADDR");
  setsockopt(fd_, SOL_SOCKET, SO_TIMESTAMP, &one, sizeof(one));  // recv_utime as LCM gives it: when it arrived
  if (a.recv_buf_size > 0) setsockopt(fd_, SOL_SOCKET, SO_RCVBUF, &a.recv_buf_size, sizeof(a.recv_buf_size));
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  addr.sin_port = htons(uint16_t(a.port));
  if (bind(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) fail("bind");
  ip_mreq m{};
  inet_pton(AF_INET, a.group.c_str(), &m.imr_multiaddr);
  m.imr_interface.s_addr = htonl(INADDR_ANY);
  if (setsockopt(fd_, IPPROTO_IP, IP_ADD_MEMBERSHIP, &m, sizeof(m)) != 0) fail("joining the group");
}

LcmSocket::~LcmSocket() {
  if (fd_ >= 0) close(fd_);
}

namespace {
std::atomic<int> next_id{1};  // subscription ids, unique in the process
}  // namespace

int LcmSocket::subscribe(const std::string& channel, Handler handler) {
  const int id = next_id++;
  subscribers_.push_back(Entry{id, channel, std::move(handler)});
  refilter();
  return id;
}

int LcmSocket::on_lost(const std::string& channel, LostHandler handler) {
  const int id = next_id++;
  lost_handlers_.push_back(LostEntry{id, channel, std::move(handler)});
  return id;
}

ChannelPattern::ChannelPattern(const std::string& pattern, const std::string& where) {
  auto* re = new regex_t;
  if (const int rc = regcomp(re, ("^(" + pattern + ")$").c_str(), REG_EXTENDED | REG_NOSUB); rc != 0) {
    char why[200];
    regerror(rc, re, why, sizeof(why));
    delete re;
    throw BusError(fmt::format("cannot subscribe to '{}' on {}: not a regular expression ({}); escape . * + ? ( ) [ ] "
                               "{{ }} | ^ $ \\ to match them as they are",
                               clip(pattern), where, why));
  }
  regex_ = std::shared_ptr<const void>(re, [](const void* r) {
    regfree(const_cast<regex_t*>(static_cast<const regex_t*>(r)));
    delete static_cast<const regex_t*>(r);
  });
  std::string name;
  for (size_t i = 0; i < pattern.size(); ++i) {
    const char c = pattern[i];
    if (c == '\\' && i + 1 < pattern.size() && !std::isalnum(static_cast<unsigned char>(pattern[i + 1]))) {
      name += pattern[++i];
    } else if (std::strchr(".[]()*+?{}|^$\\", c)) {
      return;
    } else {
      name += c;
    }
  }
  literal_ = std::move(name);
}

bool ChannelPattern::matches(const char* channel) const {
  return regexec(static_cast<const regex_t*>(regex_.get()), channel, 0, nullptr, 0) == 0;
}

int LcmSocket::subscribe_pattern(const std::string& pattern, ChannelHandler handler) {
  ChannelPattern compiled(pattern, url_);
  const int id = next_id++;
  patterns_.push_back(PatternEntry{id, std::move(compiled), std::move(handler)});
  matched_.clear();
  refilter();
  return id;
}

const std::vector<size_t>& LcmSocket::matching(std::string_view channel) {
  name_.assign(channel.data(), channel.size());
  if (auto it = matched_.find(name_); it != matched_.end()) return it->second;
  if (matched_.size() >= kMatchedChannels) matched_.clear();
  std::vector<size_t> found;
  for (size_t i = 0; i < patterns_.size(); ++i)
    if (patterns_[i].pattern.matches(name_.c_str()))
      found.push_back(i);
  return matched_.emplace(name_, std::move(found)).first->second;
}

void LcmSocket::unsubscribe(int id) {
  subscribers_.erase(std::remove_if(subscribers_.begin(), subscribers_.end(), [id](const Entry& e) { return e.id == id; }),
                     subscribers_.end());
  const size_t patterns = patterns_.size();
  patterns_.erase(std::remove_if(patterns_.begin(), patterns_.end(), [id](const PatternEntry& e) { return e.id == id; }),
                  patterns_.end());
  if (patterns_.size() != patterns) matched_.clear();
  lost_handlers_.erase(std::remove_if(lost_handlers_.begin(), lost_handlers_.end(),
                                      [id](const LostEntry& e) { return e.id == id; }),
                       lost_handlers_.end());
  refilter();
}

namespace {
// A classic BPF program for a UDP socket (offset 0: the UDP header, 8 bytes) that admits a datagram unless it is a
// whole LCM message ("LC02") on none of `names`; fragments and foreign datagrams go to the program, which counts them.
std::vector<sock_filter> channel_filter(const std::set<std::string>& names) {
  constexpr uint32_t kUdpHeader = 8, kAdmit = 0xffffffffu;
  std::vector<sock_filter> prog;
  auto stmt = [&](uint16_t code, uint32_t k) { prog.push_back(sock_filter{code, 0, 0, k}); };
  stmt(BPF_LD | BPF_W | BPF_ABS, kUdpHeader);
  prog.push_back(sock_filter{BPF_JMP | BPF_JEQ | BPF_K, 1, 0, read_be<uint32_t>(kShort)});
  stmt(BPF_RET | BPF_K, kAdmit);
  for (const std::string& name : names) {
    // The name and its NUL, compared 4, 2 and 1 bytes at a time; a mismatch jumps to the next name's first load.
    const std::string bytes = name + '\0';
    std::vector<std::pair<uint16_t, uint32_t>> loads;  // (size, offset)
    for (size_t at = 0; at < bytes.size();) {
      const size_t left = bytes.size() - at, size = left >= 4 ? 4 : left >= 2 ? 2 : 1;
      loads.emplace_back(uint16_t(size), uint32_t(at));
      at += size;
    }
    const size_t block = 2 * loads.size() + 1;
    for (size_t i = 0; i < loads.size(); ++i) {
      const auto [size, at] = loads[i];
      uint32_t value = 0;
      for (size_t b = 0; b < size; ++b) value = value << 8 | uint8_t(bytes[at + b]);
      stmt(uint16_t(BPF_LD | BPF_ABS | (size == 4 ? BPF_W : size == 2 ? BPF_H : BPF_B)),
           kUdpHeader + uint32_t(kShortHeader) + at);
      const size_t to_next = block - 2 * i - 2;  // from the instruction after this jump to the next name
      prog.push_back(sock_filter{BPF_JMP | BPF_JEQ | BPF_K, 0, uint8_t(to_next), value});
    }
    stmt(BPF_RET | BPF_K, kAdmit);
  }
  stmt(BPF_RET | BPF_K, 0);
  return prog;
}
}  // namespace

void LcmSocket::refilter() {
  std::set<std::string> names;
  bool every = subscribers_.empty() && patterns_.empty();
  for (const Entry& e : subscribers_) names.insert(e.channel);
  for (const PatternEntry& p : patterns_) {
    if (p.pattern.literal()) names.insert(*p.pattern.literal());
    else every = true;
  }
  // LCM caps a channel name at 63 bytes: a longer one never comes whole, but the jumps must stay within 8 bits.
  for (const std::string& n : names) every = every || n.size() > 100;
  std::vector<sock_filter> prog;
  if (!every) prog = channel_filter(names);
  const sock_fprog fprog{uint16_t(prog.size()), prog.data()};
  if (every || prog.size() > BPF_MAXINSNS || setsockopt(fd_, SOL_SOCKET, SO_ATTACH_FILTER, &fprog, sizeof(fprog)) != 0) {
    // Every datagram is read: the handlers still pick their channels, only the wake-ups stay.
    const int unused = 0;
    if (!filter_names_.empty()) setsockopt(fd_, SOL_SOCKET, SO_DETACH_FILTER, &unused, sizeof(unused));
    filter_names_.clear();
    return;
  }
  filter_names_.assign(names.begin(), names.end());
}

bool LcmSocket::subscribed(std::string_view channel) {
  return std::any_of(subscribers_.begin(), subscribers_.end(), [&](const Entry& e) { return e.channel == channel; }) ||
         (!patterns_.empty() && !matching(channel).empty());
}

bool LcmSocket::parse(int n, const sockaddr_in& from, std::string_view* channel, const uint8_t** payload, int* size) {
  const uint8_t* b = buf_.data();
  if (n >= kFragmentHeader && std::memcmp(b, kFragment, 4) == 0) return fragment(n, from, channel, payload, size);
  if (n < kShortHeader + 1 || std::memcmp(b, kShort, 4) != 0) {
    ++not_lcm_;
    return false;
  }
  const auto* name = reinterpret_cast<const char*>(b + kShortHeader);
  const void* nul = std::memchr(name, 0, size_t(n - kShortHeader));
  if (!nul) {
    ++not_lcm_;
    return false;
  }
  *channel = std::string_view(name, size_t(static_cast<const char*>(nul) - name));
  *payload = static_cast<const uint8_t*>(nul) + 1;
  *size = int(b + n - *payload);
  return true;
}

// LCM's reassembly: one message in progress per sender (a newer sequence number from it drops the unfinished one),
// a few senders at once (the least recently heard one gives way), the fragments in order.
bool LcmSocket::fragment(int n, const sockaddr_in& from, std::string_view* channel, const uint8_t** payload,
                         int* size) {
  const uint8_t* b = buf_.data();
  const uint32_t seqno = read_be<uint32_t>(b + 4), total = read_be<uint32_t>(b + 8), offset = read_be<uint32_t>(b + 12);
  const uint16_t number = read_be<uint16_t>(b + 16), count = read_be<uint16_t>(b + 18);
  const uint8_t* chunk = b + kFragmentHeader;
  uint32_t chunk_size = uint32_t(n - kFragmentHeader);
  if (count == 0 || number >= count || uint64_t(total) > uint64_t(count) * 65536) {  // its fragments cannot carry it
    ++not_lcm_;
    return false;
  }
  Partial* p = nullptr;
  for (Partial& q : partials_)
    if (q.active && q.addr == from.sin_addr.s_addr && q.port == from.sin_port) p = &q;
  if (p && (p->seqno != seqno || p->total != total || p->count != count)) {
    drop(*p);  // the sender moved on: its unfinished message is lost, as LCM loses it
    p->active = false;
  }
  if (!p || !p->active) {
    if (!p) {
      p = &partials_[0];
      for (Partial& q : partials_)
        if (!q.active || (p->active && q.heard_us < p->heard_us)) p = &q;
      if (p->active) drop(*p);
    }
    p->active = true;
    p->addr = from.sin_addr.s_addr;
    p->port = from.sin_port;
    p->seqno = seqno;
    p->total = total;
    p->count = count;
    p->received = 0;
    p->filled = 0;
    p->wanted = false;
    p->named = false;
    p->dropped = false;
  }
  p->heard_us = monotonic_us();
  if (number == 0 && p->received == 0) {
    const void* nul = std::memchr(chunk, 0, chunk_size);
    if (!nul) {
      ++not_lcm_;
      p->active = false;
      return false;
    }
    const size_t name_size = size_t(static_cast<const uint8_t*>(nul) - chunk);
    p->channel.assign(reinterpret_cast<const char*>(chunk), name_size);
    p->named = true;
    chunk += name_size + 1;
    chunk_size -= uint32_t(name_size + 1);
    if (subscribed(p->channel)) {
      p->wanted = total <= kMaxMessageBytes;
      if (!p->wanted) {
        ++too_large_;
        p->dropped = true;
        tell_lost(Lost{p->channel, total, true, chunk, int(std::min(chunk_size, total))});
      }
    }
  }
  if (uint64_t(offset) + chunk_size > total) {
    ++not_lcm_;
    drop(*p);
    p->active = false;
    return false;
  }
  if (number != p->received || offset != p->filled) {
    drop(*p);  // a fragment went missing (or came out of order): the rest of this message is skipped
    ++p->received;
    return false;
  }
  if (p->wanted) {  // appended, not resized and overwritten: no zero-fill of what arrives
    // A message over kKeptBytes has its whole room reserved at its first fragment, so that no read copies what
    // arrived before: growing by doubling copied up to 2 MiB in one fragment's read (4.5 ms for a 3.6 MB goal), and
    // reserving at 256 KiB copied 256 KiB into fresh pages (~1 ms: a first touch costs ~10 us on a virtual machine).
    // The room is a buffer given back to the pool (its pages touched already), or else is mapped apart and touched
    // only as fragments fill it: a sender of first fragments alone costs their pages, not the room.
    if (p->total > kKeptBytes && p->data.capacity() < p->total) {
      if (p->data.capacity() > kKeptBytes) release_room(*p, true);  // a message's, copied to its receivers
      if (p->kept.capacity() == 0) p->kept.swap(p->data);
      std::vector<uint8_t> room = pool_->take(p->total);
      if (room.capacity() >= p->total) p->data.swap(room);
      else p->data.reserve(p->total);
    }
    p->data.resize(p->filled);
    p->data.insert(p->data.end(), chunk, chunk + chunk_size);
  }
  p->filled += chunk_size;
  if (++p->received < p->count) return false;
  p->active = false;
  if (p->dropped || !p->wanted) return false;
  if (p->filled != p->total) {
    drop(*p);
    return false;
  }
  ++reassembled_;
  delivering_ = p;
  *channel = p->channel;
  *payload = p->data.data();
  *size = int(total);
  return true;
}

void LcmSocket::drop(Partial& p) {
  if (!p.dropped) {
    ++incomplete_;
    if (p.named && p.wanted) tell_lost(Lost{p.channel, p.total, false, p.data.data(), int(p.filled)});
  }
  p.wanted = false;
  p.dropped = true;
  release_room(p, false);  // an unfinished message's room is not kept: a forged sender would fill the pool
}

void LcmSocket::release_room(Partial& p, bool keep) {
  if (p.data.capacity() > kKeptBytes && !(keep && pool_->offer(p.data))) std::vector<uint8_t>().swap(p.data);
  if (p.data.capacity() == 0) p.data.swap(p.kept);
}

void LcmSocket::tell_lost(const Lost& lost) {
  for (const LostEntry& e : lost_handlers_)
    if (e.channel == lost.channel) e.handler(lost);
}

void LcmSocket::expire(int64_t now_us) {
  for (Partial& p : partials_) {
    if (p.active && now_us - p.heard_us > kFragmentTimeoutUs) {
      drop(p);
      p.active = false;
    }
    if (!p.active) release_room(p, true);  // a delivered message's (a dropped one's went at its drop)
  }
}

size_t LcmSocket::reassembly_bytes() const {
  size_t bytes = 0;
  for (const Partial& p : partials_) bytes += p.data.capacity() > kKeptBytes ? p.data.size() : p.data.capacity();
  return bytes;
}

bool LcmSocket::receive(ssize_t* n, std::string_view* channel, const uint8_t** payload, int* size) {
  sockaddr_in from{};
  iovec iov{buf_.data(), buf_.size()};
  alignas(cmsghdr) char control[CMSG_SPACE(sizeof(timeval))];
  msghdr msg{};
  msg.msg_name = &from;
  msg.msg_namelen = sizeof(from);
  msg.msg_iov = &iov;
  msg.msg_iovlen = 1;
  msg.msg_control = control;
  msg.msg_controllen = sizeof(control);
  delivering_ = nullptr;
  *n = recvmsg(fd_, &msg, MSG_DONTWAIT);
  if (*n < 0) return false;
  arrived_us_ = -1;
  for (cmsghdr* c = CMSG_FIRSTHDR(&msg); c; c = CMSG_NXTHDR(&msg, c))
    if (c->cmsg_level == SOL_SOCKET && c->cmsg_type == SCM_TIMESTAMP) {
      timeval tv{};
      std::memcpy(&tv, CMSG_DATA(c), sizeof(tv));
      arrived_us_ = int64_t(tv.tv_sec) * 1000000 + tv.tv_usec;
    }
  return parse(int(*n), from, channel, payload, size);
}

int LcmSocket::handle_queued(int max, int64_t until_us) {
  expire(monotonic_us());
  int read = 0;
  for (; read < max; ++read) {
    if (read > 0 && until_us != INT64_MAX && monotonic_us() >= until_us) break;
    ssize_t n = 0;
    std::string_view channel;
    const uint8_t* payload = nullptr;
    int size = 0;
    const bool complete = receive(&n, &channel, &payload, &size);
    if (n < 0) return errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR ? read : -1;
    if (!complete) continue;
    const lcm::ReceiveBuffer rb{const_cast<uint8_t*>(payload), uint32_t(size), arrived_us_ >= 0 ? arrived_us_ : wall_us()};
    if (delivering_ || tap_) {  // a put-together message may be taken by its one receiver (take_delivered)
      size_t receivers = 0;
      for (const Entry& e : subscribers_) receivers += e.channel == channel;
      if (!patterns_.empty()) receivers += matching(channel).size();
      if (delivering_ && (receivers != 1 || delivering_->data.capacity() <= kKeptBytes)) delivering_ = nullptr;
      if (tap_ && receivers > 0) {
        name_.assign(channel);
        tap_(rb, name_);
      }
    }
    for (const Entry& e : subscribers_)
      if (e.channel == channel) e.handler(rb);
    if (!patterns_.empty())
      for (const size_t i : matching(channel)) patterns_[i].handler(rb, name_);
    delivering_ = nullptr;
  }
  return read;
}

std::vector<uint8_t> LcmSocket::take_delivered(const lcm::ReceiveBuffer& rb) {
  std::vector<uint8_t> bytes;
  if (delivering_ && delivering_->data.data() == rb.data) {
    bytes.swap(delivering_->data);
    bytes.resize(rb.data_size);
    delivering_->data.swap(delivering_->kept);
    delivering_ = nullptr;
  } else {
    bytes.assign(static_cast<const uint8_t*>(rb.data), static_cast<const uint8_t*>(rb.data) + rb.data_size);
  }
  return bytes;
}

const uint8_t* LcmSocket::wait_for(std::string_view channel, int timeout_ms, int* size) {
  const int64_t end = monotonic_us() + int64_t(timeout_ms) * 1000;
  for (;;) {
    const int64_t left_us = end - monotonic_us();
    pollfd p{fd_, POLLIN, 0};
    if (left_us < 0 || poll(&p, 1, int((left_us + 999) / 1000)) <= 0) return nullptr;
    ssize_t n = 0;
    std::string_view got;
    const uint8_t* payload = nullptr;
    int bytes = 0;
    if (!receive(&n, &got, &payload, &bytes) || got != channel) continue;
    if (size) *size = bytes;
    return payload;
  }
}

std::string describe(const LcmSocket::Lost& lost) {
  if (lost.too_large)
    return fmt::format("a message of {} bytes on '{}' was dropped: over the {} bytes a message may have here "
                       "(docs/reliability.md, \"Limits\"); send less at a time",
                       lost.bytes, clip(std::string(lost.channel)), LcmSocket::kMaxMessageBytes);
  return fmt::format("a message of {} bytes on '{}' was lost on the way: {} of its bytes arrived in order (a fragment "
                     "was lost: raise the receive buffer with recv_buf_size in the LCM URL, or send less at a time)",
                     lost.bytes, clip(std::string(lost.channel)), lost.head_size);
}

}  // namespace lcm_control
