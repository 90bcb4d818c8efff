// bench_pingpong: the round-trip floors on their own (two processes), and the
// echo servers bench/run starts for bench_loop.
//   bench_pingpong udp-echo PORT  | bench_pingpong udp-ping PORT N WARMUP PING_BYTES PONG_BYTES
//   bench_pingpong lcm-echo URL   | bench_pingpong lcm-ping URL N WARMUP PING_BYTES PONG_BYTES
//   bench_pingpong lcm-direct-echo URL | bench_pingpong lcm-direct-ping URL N WARMUP PING_BYTES PONG_BYTES
//     (LCM packets, read from the socket on the calling thread: common/lcm_socket)
//   bench_pingpong futex-ping N WARMUP PING_BYTES PONG_BYTES
//     (the shared-memory floor: a forked echo, a futex word and the bytes copied each way, no library)
// The ping side prints "min_us p50_us p99_us max_us lost".
#include <linux/futex.h>
#include <sys/mman.h>
#include <sys/syscall.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench/pingpong.hpp"

namespace {

using namespace lcm_control::bench;

template <class Pinger>
int ping(Pinger& p, int n, int warmup) {
  const RttSummary s = measure(p, n, warmup);
  std::printf("%.2f %.2f %.2f %.2f %d\n", s.min, s.p50, s.p99, s.max, s.lost);
  return 0;
}

// An LCM pinger once its echo answers: `argv` is MODE URL N WARMUP PING_BYTES PONG_BYTES.
template <class Pinger>
int ping_lcm(char** argv, const char* echo) {
  Pinger p(argv[2], std::atoi(argv[5]), std::atoi(argv[6]));
  if (!p.good() || !p.wait_for_echo(5)) {
    std::fprintf(stderr, "bench_pingpong: no %s answers on %s\n", echo, argv[2]);
    return 1;
  }
  return ping(p, std::atoi(argv[3]), std::atoi(argv[4]));
}

// The bare futex ping-pong between two processes: the ping copies PING_BYTES into shared memory, bumps the word and
// wakes; the echo copies them out, PONG_BYTES back, bumps and wakes. What ShmLink's round trip is measured against.
class FutexPinger {
 public:
  FutexPinger(int ping_bytes, int pong_bytes) : ping_(size_t(ping_bytes), 1), pong_(size_t(pong_bytes), 2) {
    map_ = mmap(nullptr, kBytes, PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
    if (map_ == MAP_FAILED) throw std::runtime_error("mmap failed");
    word_ = new (map_) std::atomic<uint32_t>(0);
    data_ = static_cast<uint8_t*>(map_) + 64;
    child_ = fork();
    if (child_ == 0) echo();
  }
  ~FutexPinger() {
    word_->store(UINT32_MAX);
    wake();
    waitpid(child_, nullptr, 0);
    munmap(map_, kBytes);
  }
  double round_trip_us(int = 1000) {
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

 private:
  static constexpr size_t kBytes = 1 << 20;
  void wake() { syscall(SYS_futex, reinterpret_cast<uint32_t*>(word_), FUTEX_WAKE, INT_MAX, nullptr, nullptr, 0); }
  void wait_for(uint32_t v) {
    for (uint32_t w = word_->load(); w != v && w != UINT32_MAX; w = word_->load())
      syscall(SYS_futex, reinterpret_cast<uint32_t*>(word_), FUTEX_WAIT, w, nullptr, nullptr, 0);
  }
  [[noreturn]] void echo() {
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
  std::vector<uint8_t> ping_, pong_;
  void* map_ = nullptr;
  std::atomic<uint32_t>* word_ = nullptr;
  uint8_t* data_ = nullptr;
  uint32_t seq_ = 0;
  pid_t child_ = -1;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "";
  auto arg = [&](int k) { return k < argc ? std::atoi(argv[k]) : 0; };
  try {
    if (mode == "udp-echo" && argc == 3) return udp_echo(arg(2));
    if (mode == "lcm-echo" && argc == 3) return lcm_echo(argv[2]);
    if (mode == "lcm-direct-echo" && argc == 3) return lcm_direct_echo(argv[2]);
    if (mode == "lcm-direct-ping" && argc == 7) return ping_lcm<LcmDirectPinger>(argv, "lcm-direct-echo");
    if (mode == "udp-ping" && argc == 7) {
      UdpPinger p(arg(2), arg(5), arg(6));
      return ping(p, arg(3), arg(4));
    }
    if (mode == "lcm-ping" && argc == 7) return ping_lcm<LcmPinger>(argv, "lcm-echo");
    if (mode == "futex-ping" && argc == 6) {
      FutexPinger p(arg(4), arg(5));
      return ping(p, arg(2), arg(3));
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_pingpong: %s\n", e.what());
    return 1;
  }
  std::fprintf(stderr,
               "usage: bench_pingpong udp-echo PORT | udp-ping PORT N WARMUP PING_BYTES PONG_BYTES |\n"
               "       lcm-echo URL | lcm-ping URL N WARMUP PING_BYTES PONG_BYTES |\n"
               "       lcm-direct-echo URL | lcm-direct-ping URL N WARMUP PING_BYTES PONG_BYTES |\n"
               "       futex-ping N WARMUP PING_BYTES PONG_BYTES\n");
  return 2;
}
