// The fuzz payloads over real LCM against the running programs (issue 18), and over shared memory (issue 34): a
// real-time turret_bot (sim_server, controller_manager with the tutorial's
// controllers, state-publisher, state-logger) takes 2,400 hostile payloads on
// every channel they subscribe. Afterwards every process still runs, the
// robot still follows a command, and joint_states are finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <random>
#include <set>
#include <cmath>
#include <thread>

#include "bus/shm_link.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/command_source_t.hpp"
#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/sim_request_t.hpp"
#include "lcm_control/sim_response_t.hpp"
#include "test/reliability/fuzz/payloads.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/shm_segment.hpp"
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

// Commands j1 to `target` until joint_states show it there (within 0.02), at most 15 s: the robot still follows.
bool j1_reaches(lcm::LCM& lc, const lt::Recorder<joint_state_t>& states, double target) {
  float64_t cmd{};
  cmd.data = target;
  return lt::pump_until(
      lc,
      [&] {
        lc.publish("j1_controller/command", &cmd);
        if (states.messages.size() < 30) return false;
        const auto& last = states.messages.back();
        return !last.position.empty() && std::abs(last.position[0] - target) < 0.02;
      },
      15);
}

// The last 20 joint_states hold finite positions.
bool last_positions_finite(const lt::Recorder<joint_state_t>& states) {
  bool finite = true;
  for (size_t k = states.messages.size() > 20 ? states.messages.size() - 20 : 0; k < states.messages.size(); ++k)
    for (double x : states.messages[k].position) finite = finite && std::isfinite(x);
  return finite;
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
  send<sim_request_t>(lc, p, hints, "sim_server/request", n);
  const double flood_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  // Undo what a well-formed hostile message may legitimately have done (anyone on the bus may, as with ROS):
  // release the e-stop, resume a paused simulation and restore the gains, repeated until hardware/state and
  // sim_server's answers show all three took; a message sent into a subscription whose queue the flood still fills
  // is dropped by LCM.
  sleep_ms(500);  // let the flood's backlog drain
  lt::Recorder<hardware_state_t> hw(lc, "hardware/state");
  e_stop_t release{};
  release.engaged = false;
  release.source = "fuzz test";
  auto same = [](const pid_gains_t& a, const pid_gains_t& b) {
    return a.p == b.p && a.i == b.i && a.d == b.d && a.i_clamp_min == b.i_clamp_min &&
           a.i_clamp_max == b.i_clamp_max && a.antiwindup == b.antiwindup;
  };
  lt::Recorder<sim_response_t> sim_answers_seen(lc, "sim_server/response");
  sim_request_t resume{};
  resume.op = sim_request_t::RESUME;
  resume.client = "fuzz test";
  std::set<int64_t> resume_ids;
  std::mt19937_64 ids(std::random_device{}());
  auto restored = [&] {
    if (hw.messages.empty() || hw.messages.back().e_stop) return false;
    if (std::none_of(sim_answers_seen.messages.begin(), sim_answers_seen.messages.end(),
                     [&](const sim_response_t& a) { return resume_ids.count(a.request_id) && !a.paused; }))
      return false;
    for (const pid_gains_t& b : before) {
      auto it = std::find_if(gains.messages.rbegin(), gains.messages.rend(),
                             [&](const pid_gains_t& g) { return g.joint == b.joint; });
      if (it == gains.messages.rend() || !same(*it, b)) return false;
    }
    return true;
  };
  bool sim_answers = false, undone = false;
  for (int k = 0; k < 40 && !undone; ++k) {
    gains.messages.clear();
    lc.publish("e_stop", &release);
    resume.request_id = int64_t(ids() >> 1) | 1;  // not one a hostile request may have used
    resume_ids.insert(resume.request_id);
    lc.publish("sim_server/request", &resume);
    for (pid_gains_t g : before) {
      g.query = false;
      lc.publish("sim_server/gains/set", &g);
    }
    undone = lt::pump_until(lc, restored, 0.25);
    sim_answers = sim_answers || !gains.messages.empty();
  }
  EXPECT_TRUE(undone) << "e-stop " << (hw.messages.empty() ? "unknown (no hardware/state)"
                                                           : hw.messages.back().e_stop ? "engaged" : "released")
                      << ", " << gains.messages.size() << " gains answers";
  // A well-formed hostile request may have stopped or unloaded the controllers: reload the configuration
  // (stopping and unloading what is left) and spawn them again.
  lt::ChildProcess reload({lt::bin("cmctl"), "reload", "--force"}, env);
  const bool cm_answers = reload.wait(20) == 0;
  EXPECT_TRUE(cm_answers) << reload.output();
  lt::ChildProcess respawn({lt::bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller"}, env);
  EXPECT_TRUE(respawn.wait_for_output("spawner: ready", 20)) << respawn.output() << cm.output().substr(0, 2000);
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  lt::Recorder<link_poses_t> poses(lc, "link_poses");
  const auto logged_before = std::filesystem::file_size(dir + "/joint_states.csv");
  const bool reached = j1_reaches(lc, states, 0.5);
  sleep_ms(300);  // state-logger writes what it has
  // Alive: the process runs. Hung: it runs but no longer does its job (answers, publishes, writes).
  const bool logger_writes = std::filesystem::file_size(dir + "/joint_states.csv") > logged_before;
  int alive = 0, hung = 0;
  const std::pair<lt::ChildProcess*, bool> jobs[] = {
      {&sim, sim_answers}, {&cm, cm_answers}, {&publisher, !poses.messages.empty()}, {&logger, logger_writes}};
  for (const auto& [proc, works] : jobs) {
    alive += proc->running();
    hung += proc->running() && !works;
  }
  const bool finite = last_positions_finite(states);
  std::printf("RELIABILITY|fuzz|over LCM: sim_server, controller_manager, state-publisher, state-logger, 10 channels|"
              "tried=%d|ok=%d|crashes=%d|hangs=%d|%d payloads in %.1f s; afterwards j1 %s 0.5, joint_states %s\n",
              10 * n, alive == 4 && hung == 0 ? 10 * n : 0, 4 - alive, hung, 10 * n, flood_s, reached ? "reached" : "did NOT reach",
              finite ? "finite" : "NOT finite");
  EXPECT_EQ(alive, 4) << sim.output().substr(0, 2000) << cm.output().substr(0, 2000);
  EXPECT_EQ(hung, 0) << "sim answers " << sim_answers << ", controller_manager answers " << cm_answers
                     << ", link_poses " << poses.messages.size() << ", state-logger writes " << logger_writes;
  EXPECT_TRUE(reached) << "j1 at " << (states.messages.empty() ? NAN : states.messages.back().position[0]) << "\n"
                       << cm.output().substr(cm.output().size() > 3000 ? cm.output().size() - 3000 : 0) << "\n"
                       << sim.output().substr(sim.output().size() > 3000 ? sim.output().size() - 3000 : 0);
  EXPECT_TRUE(finite);
  EXPECT_LT(sim.output().size() + cm.output().size(), 300000u) << "the log grows with the flood";
}

// The hardware loop over shared memory (--hardware-url shm:NAME): a hostile process attached to the segment writes
// the fuzz payloads into both slots, and slot sizes past the slot, while the robot runs in real time. The schema walk
// rejects what is not a message (both programs count and say it), nothing crashes or hangs, and afterwards the loop
// runs again on the genuine states and the robot follows a command.
TEST(FuzzOverSharedMemory, HostileBytesInTheSlotsAreRejectedAndTheLoopRecovers) {
  const char* v = std::getenv("LCM_CONTROL_FUZZ_E2E_PAYLOADS");
  const int n = v && *v ? std::atoi(v) : 2400;
  const std::string url = lt::unique_lcm_url(), name = "fuzz-" + std::to_string(getpid());
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  const std::string urdf = lt::source("config/turret_bot.urdf"), yaml = lt::source("config/turret_bot.yaml");
  lt::ChildProcess sim({lt::bin("sim_server"), "--urdf", urdf, "--config", yaml, "--hardware-url", "shm:" + name}, env);
  lt::ChildProcess cm({lt::bin("controller_manager"), "--urdf", urdf, "--config", yaml, "--hardware-url", "shm:" + name},
                      env);
  lt::ChildProcess spawner({lt::bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller"}, env);
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 30)) << spawner.output() << cm.output() << sim.output();

  ShmLink hostile(name);
  lt::Hints hints{{"j1", "j2", "j1_motor", "j2_motor"}, {0, 1, 1000}};
  lt::Payloads p(272727);
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < n; ++k) {
    const auto s = p.next<hardware_state_t>(hints), c = p.next<hardware_command_t>(hints);
    hostile.publish("hardware/state", s.data(), s.size());
    hostile.publish("hardware/command", c.data(), c.size());
    std::this_thread::sleep_for(std::chrono::microseconds(500));  // a slot keeps the newest: let each be read
  }
  // Sizes past the slot, written over the size word of the command slot (found by its name), then the slot's
  // sequence advanced by a whole write (+2, no wake-up): sim_server finds it at its next step, unless
  // controller_manager's next command came first (it writes there too, once a period).
  {
    lt::MappedSegment seg(hostile.path());
    ASSERT_TRUE(seg.ok());
    const std::vector<uint8_t> marker(29, 0x5a);
    hostile.publish("hardware/command", marker.data(), marker.size());
    const int size_word = seg.size_word("hardware/command"), sequence_word = seg.sequence_word("hardware/command");
    ASSERT_GE(size_word, 0);
    for (int k = 0; k < 100; ++k) {
      hostile.publish("hardware/command", marker.data(), marker.size());
      sleep_ms(1);
      __atomic_store_n(&seg.words()[size_word], 0xfffffff0u, __ATOMIC_RELAXED);
      __atomic_fetch_add(&seg.words()[sequence_word], 2u, __ATOMIC_RELEASE);
      sleep_ms(2);
    }
  }
  const double flood_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  lcm::LCM lc(url);
  // A well-formed hostile command may have stopped or unloaded the controllers' joints' targets only; the controllers
  // themselves are untouched (no request channel here). j1 must reach a new command.
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  const bool reached = j1_reaches(lc, states, 0.5);
  const bool finite = last_positions_finite(states);
  const bool alive = sim.running() && cm.running();
  const bool sim_said = sim.output().find("dropped a hardware/command") != std::string::npos;
  const bool cm_said = cm.output().find("hardware/state") != std::string::npos &&
                       cm.output().find("dropped") != std::string::npos;
  // The sizes past the slot never reach a handler: sim_server names the file and counts them with its drops, in its
  // statistics once a second.
  const bool sim_said_skipped = sim.wait_for_output("past its 1 MiB slot", 3) &&
                                sim.output().find(hostile.path()) != std::string::npos;
  std::printf("RELIABILITY|fuzz|over shared memory: sim_server and controller_manager, both slots|tried=%d|ok=%d|"
              "crashes=%d|hangs=%d|%d payloads and 100 sizes past the slot in %.1f s; afterwards j1 %s 0.5, "
              "joint_states %s\n",
              2 * n + 100, alive && reached ? 2 * n + 100 : 0, alive ? 0 : 1, alive && !reached ? 1 : 0, 2 * n,
              flood_s, reached ? "reached" : "did NOT reach", finite ? "finite" : "NOT finite");
  EXPECT_TRUE(alive) << sim.output().substr(0, 2000) << cm.output().substr(0, 2000);
  EXPECT_TRUE(sim_said) << sim.output().substr(0, 3000);
  EXPECT_TRUE(cm_said) << cm.output().substr(0, 3000);
  EXPECT_TRUE(sim_said_skipped) << sim.output().substr(sim.output().size() > 3000 ? sim.output().size() - 3000 : 0);
  EXPECT_TRUE(reached) << "j1 at " << (states.messages.empty() ? NAN : states.messages.back().position[0]) << "\n"
                       << cm.output().substr(cm.output().size() > 3000 ? cm.output().size() - 3000 : 0) << "\n"
                       << sim.output().substr(sim.output().size() > 3000 ? sim.output().size() - 3000 : 0);
  EXPECT_TRUE(finite);
  EXPECT_LT(sim.output().size() + cm.output().size(), 300000u) << "the log grows with the flood";
}
