// bench_pingpong: the round-trip floors on their own (two processes), and the
// echo servers bench/run starts for bench_loop.
//   bench_pingpong udp-echo PORT  | bench_pingpong udp-ping PORT N WARMUP PING_BYTES PONG_BYTES
//   bench_pingpong lcm-echo URL   | bench_pingpong lcm-ping URL N WARMUP PING_BYTES PONG_BYTES
//   bench_pingpong lcm-direct-echo URL | bench_pingpong lcm-direct-ping URL N WARMUP PING_BYTES PONG_BYTES
//     (LCM packets, read from the socket on the calling thread: common/lcm_socket)
//   bench_pingpong futex-ping N WARMUP PING_BYTES PONG_BYTES
//     (the shared-memory floor: a forked echo, a futex word and the bytes copied each way, no library)
// The ping side prints "min_us p50_us p99_us max_us lost".

#include <cstdio>
#include <cstdlib>
#include <string>

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
