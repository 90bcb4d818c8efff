// sim_server in real time: pacing against the wall clock, the sim clock and
// statistics channels, the watchdog hold when commands stop, namespaces, and
// what a stall does under each --overrun policy.
#include <gtest/gtest.h>

#include <signal.h>
#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <cmath>
#include <thread>

#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "test/sim_server/fake_controller.hpp"

namespace lcm_control::sim::testing {
namespace {

using lcm_control::testing::Recorder;
using lcm_control::testing::sender_clock_drift_s;
using lcm_control::testing::source;

// Wall-clock assertions mean nothing when the machine runs several times more work than it has cores
// (stalls of 100+ ms were seen at a load of 10 on 2 cores); those runs skip them and say why, unless
// LCM_CONTROL_REALTIME_TESTS=force.
bool overloaded(std::string& why) {
  if (const char* force = getenv("LCM_CONTROL_REALTIME_TESTS"); force && std::string(force) == "force") return false;
  double load[1] = {0};
  const long cores = sysconf(_SC_NPROCESSORS_ONLN);
  if (getloadavg(load, 1) != 1 || load[0] <= 2.0 * double(cores)) return false;
  why = "load average " + std::to_string(load[0]) + " on " + std::to_string(cores) + " cores: no real-time timing";
  return true;
}

TEST(sim_realtime, ClockDriftIgnoresMessagesReadLateAndSeesARealDrift) {
  std::vector<int64_t> sent, arrived;
  for (int64_t k = 0; k < 2000; ++k) {
    sent.push_back(k * 1000);
    arrived.push_back(k < 100 ? 100'000 : k * 1000 + 30);  // the first 100 ms queued until the reader came
  }
  EXPECT_NEAR(sender_clock_drift_s(sent, arrived, 0.5), 0.0, 1e-9);
  for (size_t k = 1000; k < arrived.size(); ++k) arrived[k] += 20'000;  // a 20 ms stall never caught up
  EXPECT_NEAR(sender_clock_drift_s(sent, arrived, 0.5), -0.020, 1e-9);
}

TEST(sim_realtime, PacesToTheWallClockAndPublishesClockAndStatistics) {
  if (std::string why; overloaded(why)) GTEST_SKIP() << why;
  SimServerProcess server;
  Recorder<sim_clock_t> clock(server.lc, "clock");
  Recorder<loop_stats_t> stats(server.lc, "sim_server/statistics");
  std::string why;
  ASSERT_TRUE(server.start({}, source("config/turret_bot.urdf"), source("config/turret_bot.yaml"), &why)) << why;
  FakeController cm(server.lc);
  cm.pump_for(3.5);
  ASSERT_GE(clock.messages.size(), 2u);
  // Sim time against arrival time over the run: no drift beyond scheduling noise (stalls of a loaded
  // machine are caught up by stepping back to back). Clock messages that queued while this test was not
  // yet reading are not drift: the earliest arrivals at each end decide.
  std::vector<int64_t> sim_us;
  for (const auto& m : clock.messages) sim_us.push_back(m.utime);
  const double sim_s = double(sim_us.back() - sim_us.front()) * 1e-6;
  const double wall_s = double(clock.arrival_us.back() - clock.arrival_us.front()) * 1e-6;
  const double drift_s = sender_clock_drift_s(sim_us, clock.arrival_us, 0.5);
  std::printf("real time: %.4f s of sim time in %.4f s of wall time, %zu clock messages, sim clock %+.4f s "
              "ahead of the wall clock\n",
              sim_s, wall_s, clock.messages.size(), drift_s);
  EXPECT_LT(std::abs(drift_s), 0.05);
  EXPECT_EQ(clock.messages.back().utime, clock.messages.back().step * 1000);
  // The median window by cycles: a stall of a loaded machine across one window's edge moves cycles to the next.
  ASSERT_FALSE(stats.messages.empty());
  std::vector<loop_stats_t> windows = stats.messages;
  std::nth_element(windows.begin(), windows.begin() + long(windows.size() / 2), windows.end(),
                   [](const loop_stats_t& a, const loop_stats_t& b) { return a.cycles < b.cycles; });
  const loop_stats_t& s = windows[windows.size() / 2];
  EXPECT_EQ(s.process, "sim_server");
  EXPECT_NEAR(s.real_time_factor, 1.0, 0.25);
  EXPECT_NEAR(double(s.cycles), 1000, 250);
  EXPECT_NEAR(s.period_mean_us, 1000, 250);
  ASSERT_EQ(s.num_items, 3) << "the step, the publish, the robot's one hardware component";
  EXPECT_EQ(s.item_kind[2], "component");
  EXPECT_NEAR(s.item_period_mean_us[2], 1000, 250);
  std::printf("statistics: period %.1f us (jitter %.1f, max %.1f), step %.2f us mean, %lld overruns\n",
              s.period_mean_us, s.period_jitter_us, s.period_max_us, s.item_exec_mean_us[0],
              static_cast<long long>(s.overruns));
  EXPECT_FALSE(cm.states.back().lockstep);
  EXPECT_NEAR(cm.states.back().real_time_factor, 1.0, 0.25);
}

TEST(sim_realtime, WatchdogHoldsEveryActuatorWhenCommandsStopAndSaysSoOnce) {
  if (std::string why; overloaded(why)) GTEST_SKIP() << why;
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--namespace", "robot1", "--watchdog", "0.1"}, source("config/turret_bot.urdf"),
                           source("config/turret_bot.yaml"), &why))
      << why;
  FakeController cm(server.lc, "robot1");
  cm.policy = [](const hardware_state_t&, hardware_command_t& c) { c.command[0] = 1.0; };
  ASSERT_TRUE(cm.run_until_step(300, 10.0)) << server.output();
  cm.answering = false;
  const size_t said_before = server.output().size();  // a stall of this test before here may have tripped it too
  const int64_t stopped_at = cm.states.back().step;
  const double position_then = cm.states.back().position[0];
  cm.pump_for(2.0);
  const hardware_state_t& last = cm.states.back();
  EXPECT_GT(last.step, stopped_at + 1000);  // time goes on in real time
  // Held near where it was when the watchdog tripped (0.1 s later), far short of the command of 1.0; the
  // tutorial's soft j1 PID (kp 150, kd 50) brakes the moving slider onto the latched position.
  std::printf("watchdog: j1 at %.4f m when commands stopped, %.4f m (%.4f m/s) 2 s later\n", position_then,
              last.position[0], last.velocity[0]);
  EXPECT_LT(last.position[0], 0.9);
  EXPECT_GT(last.position[0], position_then - 0.01);
  EXPECT_LT(std::abs(last.velocity[0]), 0.1);
  const std::string out = server.output();
  const auto first = out.find("(watchdog)", said_before);
  ASSERT_NE(first, std::string::npos) << out;
  EXPECT_EQ(out.find("(watchdog)", first + 1), std::string::npos) << out;
  // Commands back: the hardware follows them again.
  cm.answering = true;
  cm.pump_for(1.0);
  EXPECT_NE(server.output().find("commands apply again"), std::string::npos);
  EXPECT_GT(cm.states.back().position[0], last.position[0] + 0.05);
}

// The process is stopped for 80 ms (SIGSTOP: a stall nothing else can cause on purpose). catch-up publishes every
// step it owes in a burst, and by default waits (--answer-wait-us) for the controller's answer to each state, so the
// burst still has a command per step; with --answer-wait-us 0 the burst runs on the last command and counts the
// unanswered steps missed. skip takes them without publishing, so the controller sees one step jump and no burst,
// and the statistics count them missed. Either way sim time is back with the wall clock right after.
TEST(sim_realtime, AStallIsCaughtUpInABurstOrSkippedAsAskedAndSimTimeKeepsUp) {
  if (std::string why; overloaded(why)) GTEST_SKIP() << why;
  struct Variant {
    std::string policy, answer_wait_us;
  };
  std::map<std::string, int64_t> missed_by, late_by;
  for (const Variant& v : {Variant{"catch-up", "200"}, Variant{"catch-up", "0"}, Variant{"skip", "200"}}) {
    const std::string name = "--overrun " + v.policy + " --answer-wait-us " + v.answer_wait_us;
    SCOPED_TRACE(name);
    SimServerProcess server;
    Recorder<hardware_state_t> states(server.lc, "hardware/state");
    Recorder<loop_stats_t> stats(server.lc, "sim_server/statistics");
    std::string why;
    ASSERT_TRUE(server.start({"--overrun", v.policy, "--answer-wait-us", v.answer_wait_us, "--timer-slack-ns", "1"},
                             source("config/turret_bot.urdf"), source("config/turret_bot.yaml"), &why))
        << why;
    FakeController cm(server.lc);
    ASSERT_TRUE(cm.run_until_step(300, 10.0)) << server.output();
    const size_t before = states.messages.size();
    ASSERT_EQ(kill(server.process->pid(), SIGSTOP), 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
    ASSERT_EQ(kill(server.process->pid(), SIGCONT), 0);
    cm.pump_for(1.2);
    // Back-to-back states are counted in the 150 states from the stall on, where a catch-up burst of its 80 steps is:
    // a wake-up of the sim late by over half a period elsewhere in the run also gives one, and says nothing of the
    // policy.
    int64_t jump = 0, burst = 0;
    for (size_t k = before; k < states.messages.size(); ++k) {
      jump = std::max<int64_t>(jump, states.messages[k].step - states.messages[k - 1].step - 1);
      if (k < before + 150 && states.arrival_us[k] - states.arrival_us[k - 1] < 500)
        ++burst;  // as read, not as this test got to them
    }
    // Sim time against the wall clock since the first state, at the last state.
    const double lag_ms = double(states.arrival_us.back() - states.arrival_us.front()) * 1e-3 -
                          double(states.messages.back().utime - states.messages.front().utime) * 1e-3;
    int64_t missed = 0;
    for (const auto& m : stats.messages) missed += m.missed;
    missed_by[name] = missed;
    late_by[name] = cm.late_answers;
    std::printf("%s: largest step jump %lld, %lld states less than half a period apart, wall time minus sim time "
                "%.1f ms since the first state, %lld missed\n",
                name.c_str(), static_cast<long long>(jump), static_cast<long long>(burst), lag_ms,
                static_cast<long long>(missed));
    EXPECT_LT(std::abs(lag_ms), 20);
    if (v.policy == "skip") {
      EXPECT_GE(jump, 60);
      EXPECT_GE(missed, 60);
      // Back-to-back arrivals say something about the policy only when our stall was the only one: on a loaded
      // machine (missed steps well beyond the jump) this process's own reads are late too and bunch up.
      if (missed <= jump + 40)
        EXPECT_LT(burst, 10);
      else
        std::printf("other stalls on this machine (%lld missed): back-to-back arrivals not checked\n",
                    static_cast<long long>(missed));
    } else {
      EXPECT_EQ(jump, 0);
      EXPECT_GE(burst, 60);
      if (v.answer_wait_us == "0") {
        // The burst ran on old commands: 38-83 of its 80 steps missed on an idle machine, 16 in a CI run whose
        // controller kept up with a slowed burst. Fewer than 8 would mean the burst waited for the answers.
        EXPECT_GE(missed, 8);
      }
    }
  }
  // Waiting for the answers: the burst's steps had their commands (0-1 missed on an idle machine, 44 against 93
  // while a build ran next to it), unless this test itself answered late: each such answer is a step missed for a
  // stall of the test, not of sim_server.
  const std::string waits = "--overrun catch-up --answer-wait-us 200", no_wait = "--overrun catch-up --answer-wait-us 0";
  if (late_by[waits] <= 10)
    EXPECT_LT(missed_by[waits], missed_by[no_wait]);
  else
    std::printf("this test answered %lld states more than %lld us after they arrived: missed steps not compared\n",
                static_cast<long long>(late_by[waits]), static_cast<long long>(FakeController::kLateAnswerUs));
}

}  // namespace
}  // namespace lcm_control::sim::testing
