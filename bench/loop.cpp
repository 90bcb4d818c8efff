// bench_loop: the hardware loop's round trip against a real controller_manager,
// next to its two floors, in interleaved blocks from one process. It plays the
// lockstep hardware of the URDF (hardware/state k out, wait for the
// hardware/command tagged k) and times publish -> command decoded; the floors
// are a bare LCM ping-pong and a raw UDP ping-pong with the same payload sizes
// (the encoded hardware_state_t and hardware_command_t) against
// `bench_pingpong lcm-echo` / `udp-echo`. Physics is not in it (bench_physics).
//   bench_loop --urdf U --config C --cm-url URL --lcm-url URL --udp-port P [--rounds R] [--n N] [--warmup W]
// A fourth kind, clock, is ours plus the `clock` message sim_server publishes
// right after every state (what that extra message costs the loop).
// Prints "sizes STATE_BYTES COMMAND_BYTES" and per block
//   rtt KIND ROUND MIN P50 P99 MAX N LOST     (KIND: udp, lcm, ours, clock)
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench/pingpong.hpp"
#include "bus/bus.hpp"
#include "bus/hardware_wire.hpp"
#include "bus/messages.hpp"
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/sim_clock_t.hpp"

namespace {

using namespace lcm_control;
using namespace lcm_control::bench;

// The lockstep hardware side, as sim_server does it: encode state k into a
// preallocated buffer, publish, handle until the command for step k is decoded.
class HardwarePinger {
 public:
  HardwarePinger(const std::string& url, const RobotModel& model) : lc_(url) {
    std::mt19937_64 rng(std::random_device{}());
    state_ = resting_state(model, int64_t(rng() >> 1), true);
    buf_.resize(size_t(state_.getEncodedSize()));
    // What the controller manager answers: same actuators, mode and command per actuator.
    resize(cmd_, state_.num_actuators);
    cmd_.name = state_.name;
    cmd_.mode = state_.mode;
    channel_state_ = channels::kHardwareState;
    if (lc_.good()) lc_.subscribe(channels::kHardwareCommand, &HardwarePinger::on_command, this);
  }
  bool good() const { return lc_.good(); }
  int state_bytes() const { return int(buf_.size()); }
  int command_bytes() const { return int(cmd_.getEncodedSize()); }

  // Republishes step 0 until the controller manager answers; false on timeout.
  bool wait_for_manager(double timeout_s) {
    const int64_t end = now_ns() + int64_t(timeout_s * 1e9);
    while (now_ns() < end) {
      if (round_trip_us(100) >= 0) return true;
      --step_;  // the same step again
    }
    return false;
  }

  // Also publish sim_server's per-step clock message after each state.
  void set_clock(bool on) { with_clock_ = on; }

  double round_trip_us(int timeout_ms = 1000) {
    state_.step = step_;
    state_.utime = step_ * 1000;
    state_.encode(buf_.data(), 0, int(buf_.size()));
    got_ = false;
    const int64_t t0 = now_ns();
    lc_.publish(channel_state_, buf_.data(), unsigned(buf_.size()));
    if (with_clock_) {
      clock_.utime = state_.utime;
      clock_.step = state_.step;
      clock_.encode(clock_buf_, 0, sizeof(clock_buf_));
      lc_.publish(channels::kClock, clock_buf_, unsigned(clock_.getEncodedSize()));
    }
    while (!got_)
      if (lc_.handleTimeout(timeout_ms) <= 0) break;
    const int64_t t1 = now_ns();
    ++step_;
    return got_ ? double(t1 - t0) / 1e3 : -1;
  }

 private:
  void on_command(const lcm::ReceiveBuffer* rbuf, const std::string&) {
    if (cmd_.decode(rbuf->data, 0, int(rbuf->data_size)) < 0) return;
    if (cmd_.step == step_ && cmd_.session == state_.session) got_ = true;
  }

  lcm::LCM lc_;
  std::string channel_state_;
  hardware_state_t state_{};
  hardware_command_t cmd_;  // decoded in place, like SimIo
  std::vector<uint8_t> buf_;
  int64_t step_ = 0;
  bool got_ = false;
  bool with_clock_ = false;
  sim_clock_t clock_{};
  uint8_t clock_buf_[64] = {};
};

int usage() {
  std::fprintf(stderr,
               "usage: bench_loop --urdf U --config C --cm-url URL --lcm-url URL --udp-port P [--rounds R] [--n N] "
               "[--warmup W]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string urdf, config, cm_url, lcm_url;
  int udp_port = 0, rounds = 7, n = 2000, warmup = 100;
  for (int k = 1; k + 1 < argc; k += 2) {
    const std::string a = argv[k], v = argv[k + 1];
    if (a == "--urdf") urdf = v;
    else if (a == "--config") config = v;
    else if (a == "--cm-url") cm_url = v;
    else if (a == "--lcm-url") lcm_url = v;
    else if (a == "--udp-port") udp_port = std::atoi(v.c_str());
    else if (a == "--rounds") rounds = std::atoi(v.c_str());
    else if (a == "--n") n = std::atoi(v.c_str());
    else if (a == "--warmup") warmup = std::atoi(v.c_str());
    else return usage();
  }
  if (argc % 2 == 0 || urdf.empty() || cm_url.empty() || lcm_url.empty() || udp_port <= 0) return usage();
  try {
    const RobotModel model = load_robot_model(urdf, config);
    HardwarePinger ours(cm_url, model);
    if (!ours.good()) throw std::runtime_error("LCM cannot start on " + cm_url);
    const int ping = ours.state_bytes(), pong = ours.command_bytes();
    std::printf("sizes %d %d\n", ping, pong);
    std::fflush(stdout);
    LcmPinger lcm(lcm_url, ping, pong);
    UdpPinger udp(udp_port, ping, pong);
    if (!lcm.good() || !lcm.wait_for_echo(10)) throw std::runtime_error("no lcm-echo answers on " + lcm_url);
    if (!ours.wait_for_manager(10)) throw std::runtime_error("no controller_manager answers on " + cm_url);
    if (udp.round_trip_us(2000) < 0) throw std::runtime_error("no udp-echo answers on port " + std::to_string(udp_port));
    const char* kinds[] = {"udp", "lcm", "ours", "clock"};
    for (int r = 0; r < rounds; ++r)
      for (int j = 0; j < 4; ++j) {
        const int kind = (j + r) % 4;  // rotate the order every round
        ours.set_clock(kind == 3);
        const RttSummary s = kind == 0 ? measure(udp, n, warmup) : kind == 1 ? measure(lcm, n, warmup)
                                                                           : measure(ours, n, warmup);
        std::printf("rtt %s %d %.2f %.2f %.2f %.2f %d %d\n", kinds[kind], r, s.min, s.p50, s.p99, s.max, s.n, s.lost);
        std::fflush(stdout);
      }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_loop: %s\n", e.what());
    return 1;
  }
  return 0;
}
