// bench_realtime: listens to a real-time sim_server run and reports its pacing:
// the period between consecutive hardware/state messages as the controller side
// receives them (error |period - nominal|: p50, p99, max; a step jump, as after
// a skip, counts as one long period), and what sim_server's and
// controller_manager's 1 Hz statistics say (missed cycles, overruns, the sim's
// own worst period, its real-time factor). The first `--skip` seconds are
// start-up and not counted. Exits after `--seconds` or `--idle` s (default 2) without a state.
//   bench_realtime --lcm-url URL [--seconds S] [--skip S] [--idle S] [--reader direct|lcm] [--statistics-only yes]
//   bench_realtime --timer-floor S [--period-us P] [--timer-slack-ns N] [--overrun catch-up|skip]
//   bench_realtime --chain-floor S [--period-us P]
// The listener reads the socket on its own thread as the controller manager does (--reader direct, the default), or
// through LCM's receive thread as the tools do (--reader lcm). With --statistics-only yes it takes only the 1 Hz
// statistics (the hardware loop then travels on a URL of its own, so this listener does not wake with each state):
// the figures from states are NaN or 0, the window figures and the missed counts hold; it stops --idle s after
// sim_server's last statistics.
// The second form is the floor: a bare loop sleeping to absolute 1 kHz deadlines
// (clock_nanosleep on CLOCK_MONOTONIC, what sim_server's pacing comes down to),
// printing "timer N P50_ERR P99_ERR MAX_ERR MISSED SHORT WINDOW_P99" (MISSED: deadlines woken for a period or more
// late, the steps a loop that skips would drop; SHORT: periods
// under half of it, the loop catching up after a stall, as sim_server's --overrun catch-up does; with
// --overrun skip the deadlines a stall passed are dropped, as sim_server's --overrun skip does).
// --timer-slack-ns sets the thread's timer slack first (Linux default 50000 ns
// for normal threads, which every sleep and ppoll timeout may be late by).
// Prints one line:
//   realtime N LOST P50_ERR P99_ERR MAX_ERR SIM_MAX_ERR MISSED OVERRUNS CM_MISSED RTF SIM_JITTER SHORT
//            ARRIVAL_P50_ERR ARRIVAL_P99_ERR ARRIVAL_SHORT WINDOW_P99 CM_WINDOW_P99 SIM_WINDOW_P99
// (errors in microseconds; LOST: states that never arrived here; SIM_JITTER: median over the 1 s windows of
// the standard deviation of sim_server's own period; SHORT: periods under half the nominal one, i.e. states
// that came back to back, as sim_server catches up after a stall; ARRIVAL_*: the same from recv_utime, the kernel's
// stamp of when each datagram arrived, i.e. when sim_server sent it, before any receiver woke; *WINDOW_P99: the
// median over 1 s windows of each window's period error p99, here, in controller_manager's own loop and in
// sim_server's, the last two from their statistics; the floor's WINDOW_P99 is the same of the bare loop)
// The third form is the floor of a period seen from another process (see chain_floor).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "bench/pingpong.hpp"
#include "bus/bus.hpp"
#include "bus/endpoints.hpp"
#include "bus/lcm_socket.hpp"
#include "rt/scheduling.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/loop_stats_t.hpp"

namespace {

using namespace lcm_control;
using lcm_control::bench::now_ns;
using lcm_control::bench::quantile;

struct Listener {
  int64_t skip_until_ns = 0;
  std::vector<double> period_err_us, arrival_err_us;
  int64_t last_ns = -1, last_step = -1, last_arrival_us = -1, short_arrivals = 0;
  double nominal_us = 1000, rtf = std::nan("");
  int64_t states = 0, lost = 0, short_periods = 0, missed = 0, overruns = 0, cm_missed = 0;
  double sim_max_err = 0;
  std::vector<double> sim_jitter;  // per 1 s window: the standard deviation of sim_server's own period
  std::vector<double> sim_window_p99, cm_window_p99;  // per 1 s window: each process's own period error p99

  void on_state(const lcm::ReceiveBuffer& rb, const hardware_state_t& s) {
    const int64_t now = now_ns();  // when the controller side gets it (recv_utime is the wall clock, not monotonic)
    ++states;
    nominal_us = s.period_us;
    rtf = s.real_time_factor;
    if (now >= skip_until_ns && last_ns >= 0 && s.step > last_step) {
      const double period = double(now - last_ns) / 1e3;
      period_err_us.push_back(std::abs(period - nominal_us));
      if (period < 0.5 * nominal_us) ++short_periods;
      lost += s.step - last_step - 1;
      const double arrival = double(rb.recv_utime - last_arrival_us);
      arrival_err_us.push_back(std::abs(arrival - nominal_us));
      if (arrival < 0.5 * nominal_us) ++short_arrivals;
    }
    last_ns = now;
    last_arrival_us = rb.recv_utime;
    last_step = s.step;
  }
  void on_sim_stats(const loop_stats_t& s) {
    if (now_ns() < skip_until_ns) return;
    missed += s.missed;
    overruns += s.overruns;
    if (s.cycles < 2) return;  // no period in the window
    sim_jitter.push_back(s.period_jitter_us);
    sim_window_p99.push_back(s.period_error_p99_us);
    sim_max_err = std::max({sim_max_err, s.period_max_us - nominal_us, nominal_us - s.period_min_us});
  }
  void on_cm_stats(const loop_stats_t& s) {
    if (now_ns() < skip_until_ns) return;
    cm_missed += s.missed;
    if (s.cycles > 1) cm_window_p99.push_back(s.period_error_p99_us);
  }
};

// The median over 1 s windows (per_window consecutive periods each) of each window's p99: the figure
// controller_manager and sim_server publish per window (period_error_p99_us), which a minute's worth of VM noise moves
// less than the p99 of the whole minute.
double window_p99_median(const std::vector<double>& err, size_t per_window) {
  std::vector<double> p99;
  for (size_t i = 0; per_window > 0 && i + per_window <= err.size(); i += per_window)
    p99.push_back(quantile(std::vector<double>(err.begin() + long(i), err.begin() + long(i + per_window)), 0.99));
  return quantile(p99, 0.5);
}

// Messages on `channel` decoded (bytes that are not a Msg are skipped) and handed to `f` with their ReceiveBuffer.
template <class Msg, class F>
void on(Endpoints& e, const std::string& channel, F f) {
  e.subscribe_raw(channel, [f](const lcm::ReceiveBuffer& rb) {
    Msg m;
    if (decode_guarded(m, rb.data, rb.data_size)) f(rb, m);
  });
}

// Moves `next` on by one period and sleeps to it (an absolute deadline on CLOCK_MONOTONIC).
void sleep_to_next(timespec& next, int64_t period_ns) {
  next.tv_nsec += long(period_ns);
  while (next.tv_nsec >= 1000000000L) {
    next.tv_nsec -= 1000000000L;
    ++next.tv_sec;
  }
  clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, nullptr);
}

int timer_floor(double seconds, double period_us, bool skip) {
  const int64_t period_ns = int64_t(period_us * 1e3);
  timespec next{};
  clock_gettime(CLOCK_MONOTONIC, &next);
  std::vector<double> err;
  err.reserve(size_t(seconds * 1e6 / period_us) + 1);
  int64_t last = -1, missed = 0, short_periods = 0;
  const int64_t end = now_ns() + int64_t(seconds * 1e9);
  while (now_ns() < end) {
    sleep_to_next(next, period_ns);
    const int64_t t = now_ns();
    const int64_t due = int64_t(next.tv_sec) * 1000000000LL + next.tv_nsec;
    if (const int64_t passed = (t - due) / period_ns; passed > 0) {
      missed += skip ? passed : 1;
      if (skip) {  // go on from the newest deadline passed
        const int64_t newest = due + passed * period_ns;
        next.tv_sec = time_t(newest / 1000000000LL);
        next.tv_nsec = long(newest % 1000000000LL);
      }
    }
    if (last >= 0) {
      const double period = double(t - last) / 1e3;
      err.push_back(std::abs(period - period_us));
      if (period < 0.5 * period_us) ++short_periods;
    }
    last = t;
  }
  std::printf("timer %zu %.2f %.2f %.2f %lld %lld %.2f\n", err.size(), quantile(err, 0.5), quantile(err, 0.99),
              err.empty() ? std::nan("") : *std::max_element(err.begin(), err.end()), (long long)missed,
              (long long)short_periods, window_p99_median(err, size_t(1e6 / period_us)));
  return 0;
}

// The floor of a paced sender seen from another process: a child sleeps to absolute deadlines as timer_floor does and
// sends one datagram on loopback after each; this process blocks in recv and takes the period between receipts, as a
// controller takes it between states. Prints "chain N P50_ERR P99_ERR MAX_ERR SHORT LATENCY_P50 LATENCY_P99" (latency:
// from the send to the receipt, both on CLOCK_MONOTONIC).
int chain_floor(double seconds, double period_us) {
  const int rx = socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof addr;
  if (rx < 0 || bind(rx, reinterpret_cast<sockaddr*>(&addr), len) != 0 ||
      getsockname(rx, reinterpret_cast<sockaddr*>(&addr), &len) != 0) {
    std::perror("bench_realtime --chain-floor: socket");
    return 1;
  }
  const pid_t child = fork();
  if (child < 0) {
    std::perror("bench_realtime --chain-floor: fork");
    return 1;
  }
  if (child == 0) {
    const int tx = socket(AF_INET, SOCK_DGRAM, 0);
    const int64_t period_ns = int64_t(period_us * 1e3), end = now_ns() + int64_t(seconds * 1e9);
    timespec next{};
    clock_gettime(CLOCK_MONOTONIC, &next);
    while (now_ns() < end) {
      sleep_to_next(next, period_ns);
      const int64_t t = now_ns();
      sendto(tx, &t, sizeof t, 0, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
    }
    const int64_t done = -1;
    sendto(tx, &done, sizeof done, 0, reinterpret_cast<const sockaddr*>(&addr), sizeof addr);
    _exit(0);
  }
  std::vector<double> err, latency;
  err.reserve(size_t(seconds * 1e6 / period_us) + 1);
  latency.reserve(err.capacity());
  int64_t last = -1, short_periods = 0;
  for (;;) {
    pollfd p{rx, POLLIN, 0};
    if (poll(&p, 1, 2000) <= 0) break;  // the sender is gone
    int64_t sent = 0;
    if (recv(rx, &sent, sizeof sent, 0) != sizeof sent || sent < 0) break;
    const int64_t t = now_ns();
    latency.push_back(double(t - sent) / 1e3);
    if (last >= 0) {
      const double period = double(t - last) / 1e3;
      err.push_back(std::abs(period - period_us));
      if (period < 0.5 * period_us) ++short_periods;
    }
    last = t;
  }
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);
  std::printf("chain %zu %.2f %.2f %.2f %lld %.2f %.2f\n", err.size(), quantile(err, 0.5), quantile(err, 0.99),
              err.empty() ? std::nan("") : *std::max_element(err.begin(), err.end()), (long long)short_periods,
              quantile(latency, 0.5), quantile(latency, 0.99));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string url;
  double seconds = 70, skip = 1, timer = 0, chain = 0, period_us = 1000, slack_ns = -1, idle = 2;
  bool skip_overruns = false, direct = true, stats_only = false;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string a = argv[k];
    if (a == "--lcm-url") url = argv[k + 1];
    else if (a == "--timer-floor") timer = std::atof(argv[k + 1]);
    else if (a == "--chain-floor") chain = std::atof(argv[k + 1]);
    else if (a == "--reader" && (std::string(argv[k + 1]) == "direct" || std::string(argv[k + 1]) == "lcm"))
      direct = std::string(argv[k + 1]) == "direct";
    else if (a == "--statistics-only") stats_only = std::string(argv[k + 1]) == "yes";
    else if (a == "--period-us") period_us = std::atof(argv[k + 1]);
    else if (a == "--timer-slack-ns") slack_ns = std::atof(argv[k + 1]);
    else if (a == "--seconds") seconds = std::atof(argv[k + 1]);
    else if (a == "--skip") skip = std::atof(argv[k + 1]);
    else if (a == "--idle") idle = std::atof(argv[k + 1]);
    else if (a == "--overrun") skip_overruns = std::string(argv[k + 1]) == "skip";
    else {
      std::fprintf(stderr, "usage: bench_realtime --lcm-url URL [--seconds S] [--skip S] | --timer-floor S\n");
      return 2;
    }
  }
  if (slack_ns >= 0) lcm_control::set_timer_slack(long(std::max(1.0, slack_ns)));
  if (timer > 0) return timer_floor(timer, period_us, skip_overruns);
  if (chain > 0) return chain_floor(chain, period_us);
  Listener l;
  lcm::LCM lc(url);
  if (!lc.good()) {
    std::fprintf(stderr, "bench_realtime: LCM cannot start on %s\n", url.c_str());
    return 1;
  }
  std::unique_ptr<LcmSocket> socket;  // the controller manager's own receive path (HardwareReader::Direct)
  try {
    if (direct) socket = std::make_unique<LcmSocket>(url);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_realtime: %s\n", e.what());
    return 1;
  }
  Endpoints e(lc, socket.get());  // without a socket, through LCM's receive thread as lcm-spy and the tools receive
  if (!stats_only) on<hardware_state_t>(e, channels::kHardwareState, [&](auto& rb, auto& m) { l.on_state(rb, m); });
  int64_t last_stats_ns = -1;
  on<loop_stats_t>(e, channels::kSimStatistics, [&](auto&, auto& m) {
    l.on_sim_stats(m);
    last_stats_ns = now_ns();
  });
  on<loop_stats_t>(e, channels::kCmStatistics, [&](auto&, auto& m) { l.on_cm_stats(m); });
  std::printf("listening\n");
  std::fflush(stdout);
  const int64_t start = now_ns(), end = start + int64_t(seconds * 1e9);
  bool started = false;
  while (now_ns() < end) {
    if (socket) {
      pollfd p{socket->fd(), POLLIN, 0};
      if (poll(&p, 1, 100) > 0) socket->handle_queued();
    } else {
      lc.handleTimeout(100);
    }
    const int64_t last = stats_only ? last_stats_ns : l.last_ns;  // what this listener follows
    if (!started && last >= 0) {
      started = true;
      l.skip_until_ns = now_ns() + int64_t(skip * 1e9);
    }
    if (started && now_ns() - last > int64_t(idle * 1e9)) break;  // the run is over
  }
  std::printf("realtime %zu %lld %.2f %.2f %.2f %.2f %lld %lld %lld %.4f %.2f %lld %.2f %.2f %lld %.2f %.2f %.2f\n",
              l.period_err_us.size(), (long long)l.lost,
              quantile(l.period_err_us, 0.5), quantile(l.period_err_us, 0.99),
              l.period_err_us.empty() ? std::nan("") : *std::max_element(l.period_err_us.begin(), l.period_err_us.end()),
              l.sim_max_err, (long long)l.missed, (long long)l.overruns, (long long)l.cm_missed, l.rtf,
              quantile(l.sim_jitter, 0.5), (long long)l.short_periods, quantile(l.arrival_err_us, 0.5),
              quantile(l.arrival_err_us, 0.99), (long long)l.short_arrivals,
              window_p99_median(l.period_err_us, size_t(1e6 / l.nominal_us)), quantile(l.cm_window_p99, 0.5),
              quantile(l.sim_window_p99, 0.5));
  return 0;
}
