#include "bus/shm_link.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <fcntl.h>
#include <linux/futex.h>
#include <poll.h>
#include <pwd.h>
#include <sched.h>
#include <signal.h>
#include <sys/eventfd.h>
#include <sys/file.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <ctime>

#include "bus/bus_error.hpp"
#include "rt/clock.hpp"

namespace lcm_control {

namespace {
constexpr char kMagic[32] = "lcm_control hardware loop shm";
constexpr uint32_t kVersion = 1;
constexpr int64_t kStuckUs = 100000;  // a slot or the naming lock held this long by a writer is taken over

long futex(std::atomic<uint32_t>* word, int op, uint32_t value, const timespec* timeout = nullptr, uint32_t bits = 0) {
  return syscall(SYS_futex, reinterpret_cast<uint32_t*>(word), op, value, timeout, nullptr, bits);
}

bool alive(int32_t pid) { return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM); }

std::string sanitized(const std::string& s) {
  std::string out;
  for (const char c : s) out += std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' ? c : '_';
  return out;
}
}  // namespace

bool is_shm_url(const std::string& url) { return url == "shm" || url.rfind("shm:", 0) == 0; }

std::string shm_name_of(const std::string& url, const std::string& ns) {
  if (!is_shm_url(url)) return "";
  if (url == "shm") return fmt::format("{}.{}", getuid(), ns.empty() ? "default" : sanitized(ns));
  const std::string name = url.substr(4);
  if (name.empty() || sanitized(name) != name || name.size() > 100)
    throw BusError(fmt::format("--hardware-url '{}': after shm: give a name of up to 100 letters, digits, '.', '_' "
                               "or '-' (or `shm` alone for one per namespace)",
                               url));
  return name;
}

struct alignas(64) ReaderPlace {
  std::atomic<int32_t> pid;
  std::atomic<uint32_t> doorbell;  // futex word: bumped by every ring
  std::atomic<uint32_t> waiting;   // 1 while its owner sleeps on doorbell
  std::atomic<uint32_t> mask;      // the slots it reads
};

struct alignas(64) SlotHeader {
  std::atomic<uint32_t> named;  // 1 once `channel` is set
  std::atomic<uint32_t> seq;    // odd while a writer copies in
  std::atomic<uint32_t> size;
  std::atomic<int32_t> writer;  // the reader place of the last writer
  char channel[ShmLink::kChannelBytes];
};

struct ShmLink::Segment {
  char magic[32];
  uint32_t version, slot_bytes, slots, readers;
  std::atomic<int32_t> naming;        // pid holding the lock that names slots and gives places, 0 when free
  std::atomic<uint32_t> names;        // bumped whenever a slot is named
  ReaderPlace reader[kReaders];
  SlotHeader slot[kSlots];
};

namespace {
constexpr size_t kHeaderBytes = 16384;  // the data starts here, page-aligned
constexpr size_t kSegmentBytes = kHeaderBytes + size_t(ShmLink::kSlots) * ShmLink::kSlotBytes;

// Held around naming a slot or taking a reader place; one left by a process that died is taken over.
class NamingLock {
 public:
  explicit NamingLock(std::atomic<int32_t>& word) : word_(word) {
    const int32_t me = getpid();
    const int64_t start = monotonic_us();
    for (int32_t holder = 0; !word_.compare_exchange_weak(holder, me); holder = 0) {
      if (holder != 0 && !alive(holder) && word_.compare_exchange_strong(holder, me)) return;
      if (holder != 0 && monotonic_us() - start > kStuckUs * 10 && word_.compare_exchange_strong(holder, me)) return;
      sched_yield();
    }
  }
  ~NamingLock() { word_.store(0); }

 private:
  std::atomic<int32_t>& word_;
};
}  // namespace

static_assert(std::atomic<uint32_t>::is_always_lock_free && std::atomic<int32_t>::is_always_lock_free);

namespace {
// The segments this process maps, for its SIGBUS handler. A file truncated under a mapping raises SIGBUS at the next
// access past its new end; the handler maps zeros over that whole segment instead and marks it, so the access
// completes, the link goes silent (the loop holds the robot as on a lost peer) and the process lives. Any other
// SIGBUS goes to the handler that was there before (by default, it ends the process).
struct Mapping {
  std::atomic<uintptr_t> begin{0};
  std::atomic<int> faulted{0};
};
constexpr int kMappings = 64;
Mapping mappings[kMappings];
struct sigaction previous_sigbus {};

void on_sigbus(int sig, siginfo_t* info, void* context) {
  const auto at = reinterpret_cast<uintptr_t>(info->si_addr);
  for (Mapping& m : mappings) {
    const uintptr_t b = m.begin.load(std::memory_order_acquire);
    if (b == 0 || at < b || at >= b + kSegmentBytes) continue;
    if (mmap(reinterpret_cast<void*>(b), kSegmentBytes, PROT_READ | PROT_WRITE,
             MAP_FIXED | MAP_PRIVATE | MAP_ANONYMOUS, -1, 0) != MAP_FAILED) {
      m.faulted.store(1, std::memory_order_release);
      return;
    }
  }
  if (previous_sigbus.sa_flags & SA_SIGINFO) {
    previous_sigbus.sa_sigaction(sig, info, context);
  } else if (previous_sigbus.sa_handler != SIG_DFL && previous_sigbus.sa_handler != SIG_IGN) {
    previous_sigbus.sa_handler(sig);
  } else {
    signal(SIGBUS, SIG_DFL);  // the access raises it again, and the default ends the process
  }
}

int register_mapping(void* at) {
  static const bool installed = [] {
    struct sigaction sa {};
    sa.sa_sigaction = &on_sigbus;
    sa.sa_flags = SA_SIGINFO;
    sigemptyset(&sa.sa_mask);
    return sigaction(SIGBUS, &sa, &previous_sigbus) == 0;
  }();
  if (!installed) return -1;
  for (int i = 0; i < kMappings; ++i) {
    uintptr_t free = 0;
    if (mappings[i].begin.compare_exchange_strong(free, reinterpret_cast<uintptr_t>(at))) {
      mappings[i].faulted.store(0);
      return i;
    }
  }
  return -1;
}

void unregister_mapping(int i) {
  if (i >= 0) mappings[i].begin.store(0, std::memory_order_release);
}
}  // namespace

namespace {
// "" when the open file is a regular file of this effective user that no other user may read or write, else what it is.
std::string not_ours(int fd) {
  struct stat st {};
  if (fstat(fd, &st) != 0) return fmt::format("cannot read its owner: {}", std::strerror(errno));
  if (!S_ISREG(st.st_mode)) return "it is not a regular file";
  if (st.st_uid != geteuid()) {
    const passwd* pw = getpwuid(st.st_uid);
    return fmt::format("it belongs to {}uid {}, not to this user (uid {})", pw ? fmt::format("'{}', ", pw->pw_name) : "",
                       st.st_uid, geteuid());
  }
  if ((st.st_mode & 077) != 0)
    return fmt::format("its mode is {:04o}: other users may read or write it (this program makes it 0600)",
                       st.st_mode & 07777);
  return "";
}
}  // namespace

ShmLink::ShmLink(const std::string& name) : path_("/dev/shm/lcm_control." + name), pid_(getpid()) {
  static_assert(sizeof(Segment) <= kHeaderBytes, "the header must fit before the data");
  auto fail = [&](const std::string& what) {
    if (fd_ >= 0) close(fd_);
    fd_ = -1;
    throw BusError(fmt::format("shared memory {}: {}", path_, what));
  };
  // The first process creates it under a name of its own, then links it in place: a reader never sees it half made.
  for (int attempt = 0; fd_ < 0; ++attempt) {
    if (attempt > 50) fail("it keeps disappearing while opened (another program removes it?)");
    fd_ = open(path_.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
    if (fd_ < 0 && errno != ENOENT)
      fail(fmt::format("cannot open it: {} (it belongs to another user, or is a link? have its owner or root remove "
                       "it, or give --hardware-url shm:ANOTHER_NAME)",
                       std::strerror(errno)));
    if (fd_ >= 0) {
      // A file someone else made, or left open to others, is refused: whoever can write it can read the robot's state
      // and command its joints.
      if (const std::string why = not_ours(fd_); !why.empty())
        fail(fmt::format("{}; refused: its writer could read the robot's state and move its joints. Have its owner or "
                         "root remove it, or give --hardware-url shm:ANOTHER_NAME",
                         why));
    }
    if (fd_ < 0) {
      const std::string tmp = fmt::format("{}.{}.new", path_, pid_);
      const int t = open(tmp.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
      if (t < 0) fail(fmt::format("cannot create it: {} (is /dev/shm mounted and writable?)", std::strerror(errno)));
      void* m = MAP_FAILED;
      if (ftruncate(t, off_t(kSegmentBytes)) == 0)
        m = mmap(nullptr, kSegmentBytes, PROT_READ | PROT_WRITE, MAP_SHARED, t, 0);
      if (m == MAP_FAILED) {
        const int e = errno;
        close(t);
        unlink(tmp.c_str());
        fail(fmt::format("cannot size it to {} bytes: {}", kSegmentBytes, std::strerror(e)));
      }
      auto* s = new (m) Segment{};
      std::memcpy(s->magic, kMagic, sizeof(kMagic));
      s->version = kVersion;
      s->slot_bytes = kSlotBytes;
      s->slots = kSlots;
      s->readers = kReaders;
      munmap(m, kSegmentBytes);
      flock(t, LOCK_SH);
      const bool linked = link(tmp.c_str(), path_.c_str()) == 0;
      unlink(tmp.c_str());
      if (!linked) {  // another process made it first: use theirs
        close(t);
        continue;
      }
      fd_ = t;
      break;
    }
    flock(fd_, LOCK_SH);  // the last one to close it removes it under LOCK_EX (see the destructor)
    struct stat st {};
    if (fstat(fd_, &st) != 0 || st.st_nlink == 0) {  // removed by the last user while we opened it: make it again
      close(fd_);
      fd_ = -1;
    }
  }
  struct stat st {};
  fstat(fd_, &st);
  if (size_t(st.st_size) != kSegmentBytes)
    fail(fmt::format("it is {} bytes, not the {} of this lcm_control's segment: another program's, or a version's "
                     "that is running; stop that, or remove the file",
                     st.st_size, kSegmentBytes));
  void* m = mmap(nullptr, kSegmentBytes, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
  if (m == MAP_FAILED) fail(fmt::format("cannot map it: {}", std::strerror(errno)));
  seg_ = static_cast<Segment*>(m);
  data_ = static_cast<uint8_t*>(m) + kHeaderBytes;
  mapping_ = register_mapping(m);
  if (std::memcmp(seg_->magic, kMagic, sizeof(kMagic)) != 0 || seg_->version != kVersion ||
      seg_->slot_bytes != kSlotBytes || seg_->slots != kSlots || seg_->readers != kReaders) {
    unregister_mapping(mapping_);
    munmap(m, kSegmentBytes);
    seg_ = nullptr;
    fail("it is not a segment of this lcm_control version: stop the program using it, or remove the file");
  }
  {
    NamingLock lock(seg_->naming);
    for (int p = 0; p < kReaders && me_ < 0; ++p) {
      const int32_t holder = seg_->reader[p].pid.load();
      if (holder == 0 || !alive(holder)) me_ = p;
    }
    if (me_ >= 0) {
      ReaderPlace& r = seg_->reader[me_];
      r.mask.store(0);
      r.waiting.store(0);
      r.pid.store(pid_);
    }
  }
  if (me_ < 0) {
    unregister_mapping(mapping_);
    munmap(seg_, kSegmentBytes);
    seg_ = nullptr;
    fail(fmt::format("{} processes have it open already, the most it takes: is a program started many times on "
                     "one hardware URL? give each robot its own --namespace or shm:NAME",
                     kReaders));
  }
  buf_.reserve(65536);
}

ShmLink::~ShmLink() {
  if (watcher_.joinable()) {
    stop_watch_ = true;
    eventfd_write(watch_stop_fd_, 1);
    fd_drained();
    watcher_.join();
  }
  if (watch_stop_fd_ >= 0) close(watch_stop_fd_);
  if (seg_) {
    seg_->reader[me_].mask.store(0);
    seg_->reader[me_].pid.store(0);
    unregister_mapping(mapping_);
    munmap(seg_, kSegmentBytes);
  }
  if (fd_ >= 0) {
    // Nobody else holds it open: remove it, still under the lock, so that a process opening it now makes a new one.
    if (flock(fd_, LOCK_EX | LOCK_NB) == 0) unlink(path_.c_str());
    close(fd_);
  }
}

int ShmLink::slot_of(const std::string& channel, bool claim) {
  for (int s = 0; s < kSlots; ++s)
    if (bound_[s] && slot_name_[s] == channel) return s;
  if (channel.size() >= kChannelBytes) return -1;
  auto find = [&] {
    for (int s = 0; s < kSlots; ++s) {
      const SlotHeader& h = seg_->slot[s];
      if (h.named.load(std::memory_order_acquire) && std::strncmp(h.channel, channel.c_str(), kChannelBytes) == 0)
        return s;
    }
    return -1;
  };
  int s = find();
  if (s < 0 && claim) {
    NamingLock lock(seg_->naming);
    s = find();
    for (int k = 0; k < kSlots && s < 0; ++k) {
      SlotHeader& h = seg_->slot[k];
      if (h.named.load()) continue;
      std::memset(h.channel, 0, kChannelBytes);
      std::memcpy(h.channel, channel.data(), channel.size());
      h.named.store(1, std::memory_order_release);
      seg_->names.fetch_add(1);
      s = k;
    }
  }
  if (s >= 0 && !bound_[s]) {
    bound_[s] = true;
    slot_name_[s] = channel;
    seen_[s] = seg_->slot[s].seq.load();  // what was there before we came is not news
  }
  return s;
}

void ShmLink::update_mask() {
  uint32_t mask = 0;
  for (int s = 0; s < kSlots; ++s)
    if (!slot_subs_[s].empty()) mask |= 1u << s;
  mask_ = mask;
  seg_->reader[me_].mask.store(mask);
}

int ShmLink::subscribe(const std::string& channel, Handler handler) {
  const int s = slot_of(channel, true);
  if (s < 0)
    throw BusError(fmt::format("shared memory {}: no slot for channel '{}' ({} channels at most, names under {} "
                               "bytes): give this robot a segment of its own (--hardware-url shm:NAME)",
                               path_, channel, kSlots, kChannelBytes));
  subs_.push_back(Sub{next_id_++, std::nullopt, std::move(handler), {}});
  slot_subs_[s].push_back(int(subs_.size()) - 1);
  update_mask();
  return subs_.back().id;
}

int ShmLink::subscribe_pattern(const std::string& pattern, ChannelHandler handler) {
  subs_.push_back(Sub{next_id_++, ChannelPattern(pattern, path_), {}, std::move(handler)});
  const ChannelPattern& compiled = *subs_.back().pattern;
  bind_slots();
  for (int s = 0; s < kSlots; ++s) {  // the slots already bound by this process
    if (!bound_[s] || !compiled.matches(slot_name_[s].c_str())) continue;
    auto& v = slot_subs_[s];
    if (std::find(v.begin(), v.end(), int(subs_.size()) - 1) == v.end()) v.push_back(int(subs_.size()) - 1);
  }
  update_mask();
  return subs_.back().id;
}

void ShmLink::bind_slots() {
  for (int s = 0; s < kSlots; ++s) {
    const SlotHeader& h = seg_->slot[s];
    if (bound_[s] || !h.named.load(std::memory_order_acquire)) continue;
    const std::string name(h.channel, strnlen(h.channel, kChannelBytes));
    bool wanted = false;
    for (size_t k = 0; k < subs_.size(); ++k) {
      if (!subs_[k].pattern || !subs_[k].pattern->matches(name.c_str())) continue;
      wanted = true;
      slot_subs_[s].push_back(int(k));
    }
    if (wanted && slot_of(name, false) == s) seen_[s] = 0;  // named after we subscribed: all of it is news
  }
  update_mask();
}

void ShmLink::unsubscribe(int id) {
  for (size_t k = 0; k < subs_.size(); ++k) {
    if (subs_[k].id != id) continue;
    subs_[k].handler = {};  // indices stay valid; the entry is kept empty
    subs_[k].channel_handler = {};
    subs_[k].pattern.reset();
    for (auto& v : slot_subs_) v.erase(std::remove(v.begin(), v.end(), int(k)), v.end());
  }
  update_mask();
}

void ShmLink::ring(int slot) {
  for (int p = 0; p < kReaders; ++p) {
    ReaderPlace& r = seg_->reader[p];
    if (p == me_ || r.pid.load(std::memory_order_relaxed) == 0 || !(r.mask.load(std::memory_order_relaxed) & (1u << slot)))
      continue;
    r.doorbell.fetch_add(1);
    if (r.waiting.load()) futex(&r.doorbell, FUTEX_WAKE, INT_MAX);
  }
}

int ShmLink::publish(const std::string& channel, const void* data, size_t size) {
  if (truncated()) {  // the loop is lost, but the mirror still shows the robot in lcm-spy
    if (const int s = slot_of(channel, false); s >= 0) mirror(s, channel, data, size);
    return -1;
  }
  if (size > kSlotBytes) {
    ++too_large_;
    return -1;
  }
  const int s = slot_of(channel, true);
  if (s < 0) return -1;
  SlotHeader& h = seg_->slot[s];
  uint32_t q = h.seq.load();
  int64_t stuck_since = -1;
  for (;;) {
    if (!(q & 1)) {
      if (h.seq.compare_exchange_weak(q, q + 1)) break;
      continue;
    }
    // Another writer is copying in: wait for it, and take the slot over if it died there.
    const int64_t now = monotonic_us();
    if (stuck_since < 0) stuck_since = now;
    if (now - stuck_since > kStuckUs && h.seq.compare_exchange_strong(q, q + 2)) {
      ++stolen_;
      q += 1;
      break;
    }
    sched_yield();
    const uint32_t again = h.seq.load();
    if (again != q) stuck_since = -1;
    q = again;
  }
  h.writer.store(me_, std::memory_order_relaxed);
  std::memcpy(data_ + size_t(s) * kSlotBytes, data, size);
  h.size.store(uint32_t(size), std::memory_order_relaxed);
  h.seq.store(q + 2, std::memory_order_release);
  ring(s);
  mirror(s, channel, data, size);
  return 0;
}

void ShmLink::mirror(int s, const std::string& channel, const void* data, size_t size) {
  if (!mirror_) return;
  const int64_t now = monotonic_us();
  if (now - mirrored_us_[s] < mirror_period_us_) return;
  mirrored_us_[s] = now;
  mirror_->publish(channel, data, unsigned(size));
}

bool ShmLink::news(int s, uint32_t& q) {
  if (slot_subs_[s].empty()) return false;
  const SlotHeader& h = seg_->slot[s];
  q = h.seq.load(std::memory_order_acquire);
  if (q & 1) {  // being written; held so past kStuckUs by a writer that died there, or by another program
    if (odd_since_us_[s] < 0 || odd_seq_[s] != q) {
      odd_since_us_[s] = monotonic_us();
      odd_seq_[s] = q;
    } else if (monotonic_us() - odd_since_us_[s] > kStuckUs) {
      odd_held_[s] = true;
    }
    return false;
  }
  odd_since_us_[s] = -1;
  if (q == seen_[s]) return false;
  const int32_t w = h.writer.load(std::memory_order_relaxed);
  if (w == me_) {  // our own message
    seen_[s] = q;
    return false;
  }
  if (w != last_writer_[s] && w >= 0 && w < kReaders) {
    if (last_writer_[s] >= 0 && !two_said_[s]) {  // a second writer, unless the first is gone (a restarted peer)
      const int32_t before = seg_->reader[last_writer_[s]].pid.load(), now = seg_->reader[w].pid.load();
      if (before > 0 && now > 0 && before != now && alive(before)) {
        two_writers_[s][0] = before;
        two_writers_[s][1] = now;
      }
    }
    last_writer_[s] = w;
  }
  return true;
}

bool ShmLink::truncated() const {
  return mapping_ >= 0 && mappings[mapping_].faulted.load(std::memory_order_relaxed) != 0;
}

void ShmLink::check_place() {
  ReaderPlace& r = seg_->reader[me_];
  if (r.mask.load(std::memory_order_relaxed) == mask_ && r.pid.load(std::memory_order_relaxed) == pid_) return;
  if (truncated()) return;  // zeros where the file was cut, not a rewrite
  place_rewritten_ = true;
  r.mask.store(mask_);
  r.pid.store(pid_);
}

std::string ShmLink::take_tampering_note() {
  std::vector<std::string> said;
  if (truncated() && !truncated_said_) {
    truncated_said_ = true;
    said.push_back(fmt::format("{} was truncated under this process (by a program of this user other than "
                               "sim_server and controller_manager?): its hardware loop is lost and the robot is held as "
                               "on a lost peer; stop that program and restart the robot's programs",
                               path_));
  }
  if (place_rewritten_ && !place_said_) {
    place_said_ = true;
    said.push_back(fmt::format("this process's reader place {} in {} was rewritten by another process (restored): a "
                               "program other than sim_server and controller_manager writes that file; stop it",
                               me_, path_));
  }
  for (int s = 0; s < kSlots; ++s) {
    if (odd_held_[s] && !odd_said_[s]) {
      odd_said_[s] = true;
      said.push_back(fmt::format("channel '{}' in {} was held mid-write for over {} ms: its messages are not "
                                 "delivered while it is (a writer that stopped there, or another program)",
                                 slot_name_[s], path_, kStuckUs / 1000));
    }
    if (two_writers_[s][0] != 0 && !two_said_[s]) {
      two_said_[s] = true;
      said.push_back(fmt::format("channel '{}' in {} is written by two live processes, pid {} and pid {}: one robot "
                                 "takes one sim_server and one controller_manager; stop the other, or give it its own "
                                 "--hardware-url shm:NAME",
                                 slot_name_[s], path_, two_writers_[s][0], two_writers_[s][1]));
    }
  }
  return fmt::format("{}", fmt::join(said, "; "));
}

bool ShmLink::has_new() {
  static_assert(kSlots <= 32);
  if (truncated()) return false;
  check_place();
  if (truncated()) return false;  // the check met the file's new end
  if (const uint32_t names = seg_->names.load(std::memory_order_acquire); names != names_seen_) {
    names_seen_ = names;  // a slot was named since: a pattern may want it
    bind_slots();
  }
  uint32_t q = 0;
  for (int s = 0; s < kSlots; ++s)
    if (news(s, q)) return true;
  return false;
}

bool ShmLink::take(int s, uint32_t q) {
  const SlotHeader& h = seg_->slot[s];
  for (int attempt = 0; attempt < 8; ++attempt) {
    const uint32_t size = h.size.load(std::memory_order_relaxed);
    if (size > kSlotBytes) {
      ++malformed_;
      seen_[s] = q;
      return false;
    }
    if (buf_.size() < size) buf_.resize(size);  // grows to the largest message once
    std::memcpy(buf_.data(), data_ + size_t(s) * kSlotBytes, size);
    std::atomic_thread_fence(std::memory_order_acquire);
    if (truncated()) return false;  // the copy met the file's new end: zeros, not a message
    const uint32_t again = h.seq.load(std::memory_order_relaxed);
    if (again == q) {
      seen_[s] = q;
      lcm::ReceiveBuffer rb{buf_.data(), size, wall_us()};
      for (const int k : slot_subs_[s]) {
        if (subs_[k].handler) subs_[k].handler(rb);
        if (subs_[k].channel_handler) subs_[k].channel_handler(rb, slot_name_[s]);
      }
      return true;
    }
    if (again & 1) return false;  // being written again: it rings when done
    q = again;
  }
  return false;
}

int ShmLink::handle_queued(int max) {
  if (!has_new()) return 0;
  int handled = 0;
  uint32_t q = 0;
  for (int s = 0; s < kSlots && handled < max; ++s)
    if (news(s, q) && take(s, q)) ++handled;
  return handled;
}

bool ShmLink::wait_us(int64_t timeout_us) {
  if (has_new() || fd_ready()) return true;  // no clock read on the hot path: the message is often there already
  return wait_until_us(monotonic_us() + std::max<int64_t>(0, timeout_us));
}

bool ShmLink::wait_until_us(int64_t deadline_us) {
  deadline_us = std::max<int64_t>(0, deadline_us);
  const timespec until{time_t(deadline_us / 1000000), long(deadline_us % 1000000) * 1000};  // CLOCK_MONOTONIC
  if (yield_first_ && !(has_new() || fd_ready())) {
    const int64_t start = monotonic_us();
    if (peer_prompt_) {
      const int64_t give_up = start + kYieldUs;
      const int64_t end = std::min(deadline_us, give_up);
      do {
        sched_yield();
        if (has_new() || fd_ready()) return true;
      } while (monotonic_us() < end);
      if (end == give_up) peer_prompt_ = false;  // not only the caller's deadline: the peer was silent for kYieldUs
    }
    const bool woken = sleep_until(until);
    if (woken) peer_prompt_ = monotonic_us() - start <= kYieldUs;
    return woken;
  }
  return sleep_until(until);
}

bool ShmLink::sleep_until(const timespec& until) {
  ReaderPlace& r = seg_->reader[me_];
  for (;;) {
    const uint32_t bell = r.doorbell.load();
    if (has_new() || fd_ready()) return true;
    r.waiting.store(1);
    if (has_new() || fd_ready()) {
      r.waiting.store(0);
      return true;
    }
    // An absolute deadline (FUTEX_WAIT_BITSET): the kernel ends a wait whose time has passed, no clock read here.
    const long rc = futex(&r.doorbell, FUTEX_WAIT_BITSET, bell, &until, FUTEX_BITSET_MATCH_ANY);
    const int err = errno;
    r.waiting.store(0);
    // The time ran out, or a signal came (the caller looks at its stop flag); EAGAIN: rung before the wait began.
    if (rc != 0 && err != EAGAIN) return has_new() || fd_ready();
  }
}

void ShmLink::ring_self() {
  ReaderPlace& r = seg_->reader[me_];
  r.doorbell.fetch_add(1);
  if (r.waiting.load()) futex(&r.doorbell, FUTEX_WAKE, INT_MAX);
}

void ShmLink::watch_fd(int fd) {
  if (watcher_.joinable()) return;
  watch_stop_fd_ = eventfd(0, EFD_CLOEXEC);
  watcher_ = std::thread([this, fd] {
    pollfd p[2] = {{fd, POLLIN, 0}, {watch_stop_fd_, POLLIN, 0}};
    while (!stop_watch_) {
      if (poll(p, 2, -1) < 0 && errno != EINTR) return;
      if (stop_watch_) return;
      if (!(p[0].revents & (POLLIN | POLLERR | POLLHUP))) continue;
      fd_ready_.store(1, std::memory_order_release);
      ring_self();
      while (fd_ready_.load(std::memory_order_acquire) && !stop_watch_)  // until the loop has read it
        futex(&fd_ready_, FUTEX_WAIT_PRIVATE, 1);
    }
  });
}

void ShmLink::fd_drained() {
  if (fd_ready_.exchange(0) != 0) futex(&fd_ready_, FUTEX_WAKE_PRIVATE, 1);
}

void ShmLink::mirror_to(lcm::LCM* lcm, double hz) {
  mirror_ = hz > 0 ? lcm : nullptr;
  mirror_period_us_ = hz > 0 ? int64_t(1e6 / hz) : 0;
}

}  // namespace lcm_control
