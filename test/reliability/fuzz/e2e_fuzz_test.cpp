// The fuzz payloads over real LCM against the running programs (issue 18): a
// real-time turret_bot (sim_server, controller_manager with the tutorial's
// controllers, state-publisher, state-logger) takes 2,400 hostile payloads on
// every channel they subscribe. Afterwards every process still runs, the
// robot still follows a command, and joint_states are finite.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <thread>

#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "test/reliability/fuzz/payloads.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

void sleep_ms(int ms) { std::this_thread::sleep_for(std::chrono::milliseconds(ms)); }

template <class Msg>
void send(lcm::LCM& lc, lt::Payloads& p, const lt::Hints& h, const std::string& channel, int n) {
  for (int k = 0; k < n; ++k) {
    const auto b = p.next<Msg>(h);
    lc.publish(channel, b.data(), unsigned(b.size()));
    if (k % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(5));  // 10,000 a second, not a burst
  }
}

}  // namespace

TEST(FuzzOverLcm, RunningProgramsSurviveHostilePayloadsOnEveryChannel) {
  const char* v = std::getenv("LCM_CONTROL_FUZZ_E2E_PAYLOADS");
  const int n = v && *v ? std::atoi(v) : 2400;
  const std::string url = lt::unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  const std::string dir = lt::temp_dir("fuzz_e2e");
  const std::string urdf = lt::source("config/turret_bot.urdf"), yaml = lt::source("config/turret_bot.yaml");
  lt::ChildProcess sim({lt::bin("sim_server"), "--urdf", urdf, "--config", yaml}, env);
  lt::ChildProcess cm({lt::bin("controller_manager"), "--urdf", urdf, "--config", yaml}, env);
  lt::ChildProcess spawner({lt::bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller"}, env);
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 30)) << spawner.output() << cm.output();
  lt::ChildProcess publisher({lt::bin("state-publisher"), "--urdf", urdf}, env);
  lt::ChildProcess logger({lt::bin("state-logger"), "joint_states", "--output", dir + "/joint_states.csv"}, env);
  ASSERT_TRUE(logger.wait_for_output("state-logger: logging", 15)) << logger.output();

  lcm::LCM lc(url);
  // The gains in force, to restore after the flood (a well-formed hostile message may legitimately change them).
  lt::Recorder<pid_gains_t> gains(lc, "sim_server/gains");
  auto ask = [&] {  // until sim_server is up and answers both
    for (const char* joint : {"j1", "j2"}) {
      pid_gains_t q{};
      q.owner = "sim_server";
      q.joint = joint;
      q.query = true;
      lc.publish("sim_server/gains/set", &q);
    }
    return lt::pump_until(lc, [&] { return gains.messages.size() >= 2; }, 0.5);
  };
  bool answered = false;
  for (int k = 0; k < 40 && !answered; ++k) answered = ask();
  ASSERT_TRUE(answered) << sim.output();
  const std::vector<pid_gains_t> before(gains.messages.end() - 2, gains.messages.end());
  lt::Hints hints{{"j1", "j2", "j1_motor", "j2_motor", "j1_controller", "j2_controller", "joint_state_controller"},
                  {0, 1, 1000}};
  lt::Payloads p(181818);
  const auto t0 = std::chrono::steady_clock::now();
  send<hardware_state_t>(lc, p, hints, "hardware/state", n);
  send<hardware_command_t>(lc, p, hints, "hardware/command", n);
  send<cm_request_t>(lc, p, hints, "controller_manager/request", n);
  send<command_source_t>(lc, p, hints, "controller_manager/command_source", n);
  send<float64_t>(lc, p, hints, "j1_controller/command", n);
  send<float64_t>(lc, p, hints, "j2_controller/command", n);
  send<joint_state_t>(lc, p, hints, "joint_states", n);
  send<e_stop_t>(lc, p, hints, "e_stop", n);
  send<pid_gains_t>(lc, p, hints, "sim_server/gains/set", n);
  const double flood_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Undo what a well-formed hostile message may legitimately have done: release the e-stop, restore the gains.
  e_stop_t release{};
  release.engaged = false;
  release.source = "fuzz test";
  for (int k = 0; k < 3; ++k) lc.publish("e_stop", &release);
  for (pid_gains_t g : before) {
    g.query = false;
    lc.publish("sim_server/gains/set", &g);
  }
  // A well-formed hostile request may have stopped or unloaded the controllers (anyone on the bus may, as with
  // ROS): reload the configuration (stopping and unloading what is left) and spawn them again.
  sleep_ms(500);  // let the flood's backlog drain
  lt::ChildProcess reload({lt::bin("cmctl"), "reload", "--force"}, env);
  EXPECT_EQ(reload.wait(20), 0) << reload.output();
  lt::ChildProcess respawn({lt::bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller"}, env);
  EXPECT_TRUE(respawn.wait_for_output("spawner: ready", 20)) << respawn.output() << cm.output().substr(0, 2000);
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  float64_t cmd{};
  cmd.data = 0.5;
  const bool reached = lt::pump_until(
      lc,
      [&] {
        lc.publish("e_stop", &release);  // again and again: a release sent into the flood's backlog can be dropped
        lc.publish("j1_controller/command", &cmd);
        if (states.messages.size() < 30) return false;
        const auto& last = states.messages.back();
        return !last.position.empty() && std::abs(last.position[0] - 0.5) < 0.02;
      },
      15);
  int alive = 0;
  for (lt::ChildProcess* proc : {&sim, &cm, &publisher, &logger}) alive += proc->running();
  bool finite = true;
  for (size_t k = states.messages.size() > 20 ? states.messages.size() - 20 : 0; k < states.messages.size(); ++k)
    for (double x : states.messages[k].position) finite = finite && std::isfinite(x);
  std::printf("RELIABILITY|fuzz|over LCM: sim_server, controller_manager, state-publisher, state-logger, 9 channels|"
              "tried=%d|ok=%d|crashes=%d|hangs=0|%d payloads in %.1f s; afterwards j1 %s 0.5, joint_states %s\n",
              9 * n, alive == 4 ? 9 * n : 0, 4 - alive, 9 * n, flood_s, reached ? "reached" : "did NOT reach",
              finite ? "finite" : "NOT finite");
  EXPECT_EQ(alive, 4) << sim.output().substr(0, 2000) << cm.output().substr(0, 2000);
  EXPECT_TRUE(reached) << "j1 at " << (states.messages.empty() ? NAN : states.messages.back().position[0]) << "\n"
                       << cm.output().substr(cm.output().size() > 3000 ? cm.output().size() - 3000 : 0) << "\n"
                       << sim.output().substr(sim.output().size() > 3000 ? sim.output().size() - 3000 : 0);
  EXPECT_TRUE(finite);
  EXPECT_LT(sim.output().size() + cm.output().size(), 300000u) << "the log grows with the flood";
}
