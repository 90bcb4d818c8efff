#include "rt/stop_signal.hpp"

#include <signal.h>

#include <initializer_list>

namespace lcm_control {

namespace {
std::atomic<int> g_signal{0};
std::atomic<bool> g_stop{false};
void on_signal(int sig) {
  g_signal.store(sig);
  g_stop.store(true);
}
}  // namespace

void install_stop_signals(bool restart_interrupted_calls) {
  for (int sig : {SIGINT, SIGTERM}) {
    struct sigaction sa {};
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    if (restart_interrupted_calls) sigaddset(&sa.sa_mask, sig);
    sa.sa_flags = restart_interrupted_calls ? SA_RESTART : 0;
    sigaction(sig, &sa, nullptr);
  }
}

bool stop_requested() { return g_signal.load() != 0; }
int stop_signal() { return g_signal.load(); }
const std::atomic<bool>& stop_flag() { return g_stop; }
void request_stop(int sig) { on_signal(sig); }
int clear_stop() {
  g_stop.store(false);
  return g_signal.exchange(0);
}

}  // namespace lcm_control
