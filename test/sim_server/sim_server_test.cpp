// The real sim_server program in lockstep against a fake controller on a
// per-test LCM URL: determinism across processes, run-time gains, e-stop,
// transmissions on the wire, dropped commands, waiting; plus start-up errors
// and signals.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <fstream>
#include <regex>

#include "bus/messages.hpp"
#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "test/sim_server/fake_controller.hpp"

namespace lcm_control::sim::testing {
namespace {

using lcm_control::testing::ChildProcess;
using lcm_control::testing::Recorder;
using lcm_control::testing::bin;
using lcm_control::testing::source;

const std::string kTurretUrdf = source("config/turret_bot.urdf");
const std::string kTurretYaml = source("config/turret_bot.yaml");
const std::string kData = SIM_TEST_DATA;

// Lockstep session with commands j1 = 0.5 + 0.4 sin(k/333), j2 = 3 sin(k/500): every state of 10,000 steps.
std::vector<hardware_state_t> lockstep_run(int steps) {
  SimServerProcess server;
  std::string why;
  if (!server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kTurretUrdf, kTurretYaml, &why)) {
    ADD_FAILURE() << why;
    return {};
  }
  FakeController cm(server.lc);
  cm.policy = [](const hardware_state_t& s, hardware_command_t& c) {
    c.command[0] = 0.5 + 0.4 * std::sin(double(s.step) * 0.003);
    c.command[1] = 3.0 * std::sin(double(s.step) * 0.002);
  };
  EXPECT_TRUE(cm.run_until_step(steps, 60.0)) << server.output();
  return cm.states;
}

// sim_server's dropped commands as its statistics count them, once `at_least` are counted (or after 5 s).
int64_t dropped_commands(SimServerProcess& server, const Recorder<loop_stats_t>& stats, int64_t at_least) {
  int64_t dropped = 0;
  lcm_control::testing::pump_until(server.lc, [&] {
    dropped = 0;
    for (const auto& m : stats.messages) dropped += m.dropped;
    return dropped >= at_least;
  }, 5.0);
  return dropped;
}

TEST(sim_e2e, LockstepRunsWithTheSameCommandsAreBitIdenticalFor10000Steps) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto a = lockstep_run(10000);
  const auto b = lockstep_run(10000);
  std::printf("two lockstep runs of 10,000 steps in %.2f s\n",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  ASSERT_GE(a.size(), 10001u);
  ASSERT_GE(b.size(), 10001u);
  EXPECT_NE(a[0].session, b[0].session);
  for (size_t k = 0; k <= 10000; ++k) {
    ASSERT_EQ(a[k].step, int64_t(k));
    ASSERT_EQ(b[k].step, int64_t(k));
    ASSERT_EQ(a[k].utime, int64_t(k) * 1000);
    for (int i = 0; i < 2; ++i) {
      ASSERT_EQ(0, std::memcmp(&a[k].position[i], &b[k].position[i], sizeof(double))) << "step " << k;
      ASSERT_EQ(0, std::memcmp(&a[k].velocity[i], &b[k].velocity[i], sizeof(double))) << "step " << k;
      ASSERT_EQ(0, std::memcmp(&a[k].effort[i], &b[k].effort[i], sizeof(double))) << "step " << k;
    }
  }
  EXPECT_GT(std::abs(a[10000].position[1]), 0.1);  // it did move
}

TEST(sim_e2e, GainsSetAtRunTimeActOnTheNextStepAndAreEchoed) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kTurretUrdf, kTurretYaml, &why)) << why;
  Recorder<pid_gains_t> echo(server.lc, "sim_server/gains");
  FakeController cm(server.lc);
  constexpr int64_t kChange = 200;
  cm.policy = [](const hardware_state_t&, hardware_command_t& c) { c.command[1] = 1.0; };
  cm.before_answer = [&](const hardware_state_t& s) {
    if (s.step != kChange) return;
    pid_gains_t g{};
    g.request_id = 7;
    g.owner = "sim_server";
    g.joint = "j2";
    g.p = 20;
    g.d = 1;
    server.lc.publish("sim_server/gains/set", &g);
  };
  ASSERT_TRUE(cm.run_until_step(kChange + 2, 20.0)) << server.output();
  ASSERT_TRUE(lcm_control::testing::pump_until(server.lc, [&] { return !echo.messages.empty(); }, 5.0));
  const pid_gains_t& answer = echo.messages.front();
  EXPECT_TRUE(answer.ok) << answer.message;
  EXPECT_EQ(answer.request_id, 7);
  EXPECT_EQ(answer.joint, "j2");
  EXPECT_EQ(answer.p, 20);
  EXPECT_EQ(answer.d, 1);
  // Effort of the step k -> k+1, reported in state k+1: p*e_k + d*(e_k - e_{k-1})/dt, e = 1 - position.
  auto e = [&](int64_t k) { return 1.0 - cm.states[k].position[1]; };
  auto effort = [&](int64_t k) { return cm.states[k].effort[1]; };
  EXPECT_NEAR(effort(kChange), 1.0 * e(kChange - 1) + 0.3 * (e(kChange - 1) - e(kChange - 2)) / 1e-3, 1e-9);
  EXPECT_NEAR(effort(kChange + 1), 20.0 * e(kChange) + 1.0 * (e(kChange) - e(kChange - 1)) / 1e-3, 1e-9);

  // A query answers with the gains in force; a direct-mode or unknown joint is refused.
  pid_gains_t q{};
  q.request_id = 8;
  q.joint = "j2";
  q.query = true;
  server.lc.publish("sim_server/gains/set", &q);
  q.request_id = 9;
  q.joint = "nope";
  server.lc.publish("sim_server/gains/set", &q);
  ASSERT_TRUE(lcm_control::testing::pump_until(server.lc, [&] { return echo.messages.size() >= 3; }, 5.0));
  EXPECT_TRUE(echo.messages[1].ok);
  EXPECT_EQ(echo.messages[1].p, 20);
  EXPECT_FALSE(echo.messages[2].ok);
  EXPECT_NE(echo.messages[2].message.find("j2"), std::string::npos) << echo.messages[2].message;
}

TEST(sim_e2e, EStopHoldsTheJointWithin1mmUnderAContraryCommand) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kTurretUrdf, kTurretYaml, &why)) << why;
  FakeController cm(server.lc);
  constexpr int64_t kEngage = 6000, kRelease = 9000;  // engaged once j1 has settled at 0.5
  cm.policy = [](const hardware_state_t& s, hardware_command_t& c) {
    c.command[0] = s.step < kEngage ? 0.5 : 0.0;
    c.command[1] = 0.0;
  };
  cm.before_answer = [&](const hardware_state_t& s) {
    if (s.step != kEngage && s.step != kRelease) return;
    e_stop_t e{};
    e.engaged = s.step == kEngage;
    e.source = "sim_e2e";
    server.lc.publish("e_stop", &e);
  };
  ASSERT_TRUE(cm.run_until_step(kRelease + 3000, 30.0)) << server.output();
  const double latched = cm.states[kEngage].position[0];
  ASSERT_NEAR(latched, 0.5, 1e-3);
  double worst = 0;
  for (int64_t k = kEngage + 1; k <= kRelease; ++k) {
    worst = std::max(worst, std::abs(cm.states[k].position[0] - latched));
    ASSERT_TRUE(cm.states[k].e_stop) << k;
  }
  std::printf("e-stop over LCM: j1 moved at most %.3g m under a command of 0\n", worst);
  EXPECT_LT(worst, 1e-3);
  EXPECT_FALSE(cm.states.back().e_stop);
  EXPECT_LT(cm.states.back().position[0], 0.2);  // released: the command of 0 applies again
  EXPECT_NE(server.output().find("e-stop engaged by 'sim_e2e'"), std::string::npos) << server.output();
}

// modes_bot: t_pid_motor to 2.0 (actuator units), the other position actuators hold, the rest get 0.
void command_pid_motor_to_2(const hardware_state_t& s, hardware_command_t& c) {
  for (int i = 0; i < s.num_actuators; ++i)
    c.command[i] = s.name[i] == "t_pid_motor" ? 2.0 : s.mode[i] == hardware_command_t::MODE_POSITION ? s.position[i]
                                                                                                      : 0.0;
}

TEST(sim_e2e, ActuatorSpaceOnTheWireReductionTwoMovesTheJointToHalfTheCommand) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kData + "/modes_bot.urdf", kData + "/modes_bot.yaml", &why)) << why;
  FakeController cm(server.lc);
  cm.policy = command_pid_motor_to_2;
  ASSERT_TRUE(cm.run_until_step(3000, 20.0)) << server.output();
  const hardware_state_t& s = cm.states.back();
  ASSERT_EQ(s.num_actuators, 5);
  EXPECT_EQ(s.name[0], "t_pid_motor");
  EXPECT_EQ(s.mode[2], hardware_command_t::MODE_VELOCITY);
  EXPECT_NEAR(s.position[0], 2.0, 2e-3);  // actuator units: the joint is at 1.0 rad
  EXPECT_NE(server.output().find("position direct (no pid_gains)"), std::string::npos);
}

// docs/hardware-protocol.md: actuators are matched by name, so a command may list them in any order; one that does not
// name each of the robot's actuators exactly once is dropped and says which.
TEST(sim_e2e, CommandActuatorsAreMatchedByNameInAnyOrder) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kData + "/modes_bot.urdf", kData + "/modes_bot.yaml", &why)) << why;
  Recorder<loop_stats_t> stats(server.lc, "sim_server/statistics");
  FakeController cm(server.lc);
  cm.policy = [](const hardware_state_t& s, hardware_command_t& c) {
    command_pid_motor_to_2(s, c);
    std::reverse(c.name.begin(), c.name.end());
    std::reverse(c.mode.begin(), c.mode.end());
    std::reverse(c.command.begin(), c.command.end());
  };
  std::string ghost;
  cm.before_answer = [&](const hardware_state_t& s) {
    if (s.step != 100) return;
    hardware_command_t c;
    resize(c, s.num_actuators);
    c.step = s.step;
    c.session = s.session;
    c.name = s.name;
    c.mode = s.mode;
    ghost = c.name[4];
    c.name[4] = "ghost_motor";
    cm.publish_command(c);
  };
  ASSERT_TRUE(cm.run_until_step(3000, 20.0)) << server.output();
  const hardware_state_t& s = cm.states.back();
  ASSERT_EQ(s.name[0], "t_pid_motor");
  EXPECT_NEAR(s.position[0], 2.0, 2e-3);  // reversed on the wire, applied to the right actuator
  EXPECT_EQ(dropped_commands(server, stats, 1), 1) << server.output();
  EXPECT_NE(server.output().find(fmt::format(
                "its actuators are not this robot's: missing actuator(s) '{}'; unknown actuator(s) 'ghost_motor'", ghost)),
            std::string::npos)
      << server.output();
}

TEST(sim_e2e, ControlRateBelowThePhysicsRateSetsThePeriodAndSimTime) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1", "--physics-rate", "2000", "--control-rate",
                            "500", "--duration", "0.2"},
                           kTurretUrdf, kTurretYaml, &why))
      << why;
  FakeController cm(server.lc);
  ASSERT_TRUE(cm.run_until_step(100, 10.0)) << server.output();
  EXPECT_EQ(cm.states.back().period_us, 2000);
  EXPECT_EQ(cm.states.back().utime, 200000);
  EXPECT_EQ(server.process->wait(5.0), 0) << server.output();  // --duration 0.2 s of sim time: done
}

// The last line says how fast the run went and what a physics step took, so that a lockstep user can tell the
// physics from the hand-over (sim_server's own clock: neither figure is zero once steps were taken).
TEST(sim_e2e, TheLastLineSaysTheRealTimeFactorAndWhatAPhysicsStepTook) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1", "--duration", "0.3"}, kTurretUrdf,
                           kTurretYaml, &why))
      << why;
  FakeController cm(server.lc);
  ASSERT_TRUE(cm.run_until_step(300, 10.0)) << server.output();
  ASSERT_EQ(server.process->wait(5.0), 0) << server.output();
  const std::string out = server.output();
  std::smatch m;
  ASSERT_TRUE(std::regex_search(out, m, std::regex(R"(stopped at step 300 \(sim time 0\.300 s\); 0 commands dropped; )"
                                                   R"(([0-9.]+)x real time, physics ([0-9.e+-]+) µs a step)")))
      << out;
  EXPECT_GT(std::stod(m[1]), 0.0) << out;
  EXPECT_GT(std::stod(m[2]), 0.0) << out;
  EXPECT_LT(std::stod(m[2]), 1e5) << out;  // a turret_bot step: far below 0.1 s
}

// `clock` at --clock-rate in sim time: by default 100 Hz (every 10th step at 1 kHz), every step with 0.
TEST(sim_e2e, ClockComesAtItsRateInSimTimeAndEveryStepWithRateZero) {
  for (const std::string rate : {"", "0", "250"}) {
    SimServerProcess server;
    Recorder<sim_clock_t> clock(server.lc, "clock");
    std::vector<std::string> flags{"--mode", "lockstep", "--lockstep-timeout", "0.1", "--duration", "0.1"};
    if (!rate.empty()) flags.insert(flags.end(), {"--clock-rate", rate});
    std::string why;
    ASSERT_TRUE(server.start(flags, kTurretUrdf, kTurretYaml, &why)) << why;
    FakeController cm(server.lc);
    ASSERT_TRUE(cm.run_until_step(100, 10.0)) << server.output();
    EXPECT_EQ(server.process->wait(5.0), 0) << server.output();
    const int64_t every = rate == "0" ? 1 : rate == "250" ? 4 : 10;
    lcm_control::testing::pump_until(server.lc, [&] { return clock.messages.size() > size_t(100 / every); }, 2.0);
    ASSERT_EQ(clock.messages.size(), size_t(100 / every + 1)) << "--clock-rate '" << rate << "'";
    for (size_t k = 0; k < clock.messages.size(); ++k) {
      EXPECT_EQ(clock.messages[k].step, int64_t(k) * every) << rate;
      EXPECT_EQ(clock.messages[k].utime, int64_t(k) * every * 1000) << rate;
    }
    EXPECT_NE(server.output().find(fmt::format("clock {} Hz", rate == "0" ? 1000 : rate == "250" ? 250 : 100)),
              std::string::npos)
        << server.output();
  }
}

TEST(sim_e2e, MalformedNanWrongSizeAndForeignCommandsAreDroppedAndCounted) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kTurretUrdf, kTurretYaml, &why)) << why;
  Recorder<loop_stats_t> stats(server.lc, "sim_server/statistics");
  FakeController cm(server.lc);
  cm.policy = [](const hardware_state_t&, hardware_command_t& c) { c.command[1] = 1.0; };
  cm.before_answer = [&](const hardware_state_t& s) {
    if (s.step != 100) return;
    hardware_command_t bad;
    resize(bad, 2);
    bad.step = s.step;
    bad.session = s.session;
    bad.name = s.name;
    bad.mode = s.mode;
    bad.command = {NAN, 0.0};
    cm.publish_command(bad);  // NaN
    bad.command = {0.0, INFINITY};
    cm.publish_command(bad);  // Inf
    hardware_command_t one = bad;
    resize(one, 1);
    one.command[0] = 0.0;
    cm.publish_command(one);  // wrong size
    bad.command = {0.0, 0.0};
    bad.session = s.session + 1;
    cm.publish_command(bad);  // another session
    bad.session = s.session;
    const char garbage[] = "not an lcm message at all, but long enough to be looked at";
    server.lc.publish(cm.command_channel(), garbage, sizeof garbage);
    bad.mode = s.mode;
    std::vector<uint8_t> bytes(size_t(bad.getEncodedSize()));
    bad.encode(bytes.data(), 0, int(bytes.size()));
    for (uint32_t n : {0xFFFFFFFFu, 67108866u}) {  // negative; one bit flipped from 2
      for (int k = 0; k < 4; ++k) bytes[32 + k] = uint8_t(n >> (24 - 8 * k));
      server.lc.publish(cm.command_channel(), bytes.data(), unsigned(bytes.size()));
    }
  };
  ASSERT_TRUE(cm.run_until_step(150, 20.0)) << server.output();
  EXPECT_EQ(dropped_commands(server, stats, 7), 7) << server.output();
  for (const auto& s : cm.states)
    for (int i = 0; i < 2; ++i) ASSERT_TRUE(std::isfinite(s.position[i]) && std::isfinite(s.effort[i])) << s.step;
  EXPECT_NE(server.output().find("dropped a hardware/command"), std::string::npos);
  ASSERT_FALSE(stats.messages.empty());
  EXPECT_EQ(stats.messages.back().process, "sim_server");
}

// A mode the joint does not offer holds that actuator, is counted and said once; the rest of the command applies.
TEST(sim_e2e, AModeTheJointDoesNotOfferHoldsThatActuatorAndIsSaidOnce) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kTurretUrdf, kTurretYaml, &why)) << why;
  FakeController cm(server.lc);
  cm.policy = [](const hardware_state_t& s, hardware_command_t& c) {
    c.command[1] = 1.0;
    if (s.step >= 100 && s.step < 300) {
      c.mode[0] = hardware_command_t::MODE_VELOCITY;  // j1 is a position actuator
      c.command[0] = 5.0;
    }
  };
  ASSERT_TRUE(cm.run_until_step(400, 20.0)) << server.output();
  const hardware_state_t& at100 = cm.states.at(100);
  const hardware_state_t& at300 = cm.states.at(300);
  EXPECT_EQ(at300.mode[0], hardware_command_t::MODE_POSITION);
  EXPECT_NEAR(at300.position[0], at100.position[0], 1e-6);  // held
  EXPECT_GT(std::abs(at300.position[1] - at100.position[1]), 0.01);  // j2 kept its commands
  const std::string out = server.output();
  const std::string said = "actuator 'a1' (joint 'j1') got a velocity command at step 100, but its joint offers "
                           "only position";
  EXPECT_NE(out.find(said), std::string::npos) << out;
  EXPECT_EQ(out.find(said, out.find(said) + 1), std::string::npos) << "said more than once:\n" << out;
  server.process->stop(10);
  EXPECT_NE(server.output().find("0 commands dropped; 200 actuator commands in a mode not offered"), std::string::npos)
      << server.output();
}

TEST(sim_e2e, ACommandFromAFutureStepIsDroppedAndGenuineCommandsStillApply) {
  // Real time: a forged command with the live session and step INT64_MAX must not make every later command stale.
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--watchdog", "0.5"}, kTurretUrdf, kTurretYaml, &why)) << why;
  FakeController cm(server.lc);
  int64_t first = -1;
  cm.policy = [&](const hardware_state_t& s, hardware_command_t& c) {
    if (first < 0) first = s.step;
    c.command[0] = s.step - first < 100 ? 0.0 : 0.5;
  };
  bool forged = false;
  cm.before_answer = [&](const hardware_state_t& s) {
    if (forged || s.step - first < 50) return;
    forged = true;
    hardware_command_t bad;
    resize(bad, s.num_actuators);
    bad.step = INT64_MAX;
    bad.session = s.session;
    bad.name = s.name;
    bad.mode = s.mode;
    bad.command = {0.0, 0.0};
    cm.publish_command(bad);
  };
  ASSERT_TRUE(cm.run_until_step(2500, 30.0)) << server.output();
  ASSERT_TRUE(forged);
  EXPECT_NEAR(cm.states.back().position[0], 0.5, 0.01) << server.output();
  EXPECT_NE(server.output().find("is ahead of the hardware's step"), std::string::npos) << server.output();
  EXPECT_EQ(server.output().find("watchdog"), std::string::npos) << server.output();
}

TEST(sim_e2e, CommandsAnsweringStatesOlderThanTheWatchdogAreStale) {
  // Real time: a controller manager stopped (SIGSTOP) and resumed answers its backlog of old states. Those commands
  // must not drive the robot; a command a few steps late still does.
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--watchdog", "0.1"}, kTurretUrdf, kTurretYaml, &why)) << why;
  FakeController cm(server.lc);
  int64_t first = -1;
  cm.policy = [&](const hardware_state_t& s, hardware_command_t& c) {
    if (first < 0) first = s.step;
    c.command[0] = 0.5;
    c.step = s.step - (s.step - first < 1500 ? 500 : 50);  // 500 steps old, then 50 (the watchdog is 100)
  };
  ASSERT_TRUE(cm.run_until_step(first + 1450, 30.0)) << server.output();
  double before = 0;
  for (const auto& st : cm.states) before = std::max(before, std::abs(st.position[0]));
  EXPECT_LT(before, 0.01) << "stale commands moved j1";
  ASSERT_TRUE(cm.run_until_step(first + 3500, 30.0)) << server.output();
  EXPECT_NEAR(cm.states.back().position[0], 0.5, 0.01) << server.output();
}

TEST(sim_e2e, LockstepWaitsRepublishesAndSaysSoOnce) {
  SimServerProcess server;
  std::string why;
  ASSERT_TRUE(server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1"}, kTurretUrdf, kTurretYaml, &why)) << why;
  FakeController cm(server.lc);
  cm.answering = false;
  cm.pump_for(0.6);
  ASSERT_EQ(cm.states.size(), 1u);
  EXPECT_EQ(cm.states[0].step, 0);
  EXPECT_TRUE(cm.states[0].lockstep);
  EXPECT_GE(cm.republished, 3);
  cm.answering = true;
  ASSERT_TRUE(cm.run_until_step(100, 10.0));  // a late controller picks up the republished state
  const std::string out = server.output();
  const auto first = out.find("waiting for the hardware/command of step 0");
  ASSERT_NE(first, std::string::npos) << out;
  // Said once for this wait (a stall of this test while it answered the next 100 steps would be another wait).
  EXPECT_EQ(out.find("waiting for the hardware/command of step 0", first + 1), std::string::npos) << out;
}

TEST(sim_e2e, SigintAndSigtermExitZeroQuickly) {
  for (int sig : {SIGINT, SIGTERM}) {
    SimServerProcess server;
    std::string why;
    ASSERT_TRUE(server.start({}, kTurretUrdf, kTurretYaml, &why)) << why;
    const auto t0 = std::chrono::steady_clock::now();
    EXPECT_EQ(server.process->stop(5.0, sig), 0) << server.output();
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 1.0);
    EXPECT_NE(server.output().find("stopped at step"), std::string::npos);
  }
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  size_t start = 0;
  for (size_t nl; (nl = text.find('\n', start)) != std::string::npos; start = nl + 1)
    out.push_back(text.substr(start, nl - start));
  if (start < text.size()) out.push_back(text.substr(start));
  return out;
}

TEST(sim_e2e, BadUrdfOrConfigGivesOneClearLineAndANonZeroExit) {
  const std::string dir = lcm_control::testing::temp_dir("sim_bad");
  std::ofstream(dir + "/broken.urdf") << "<robot name=\"x\"><link name=\"a\"></robot>";
  std::ofstream(dir + "/broken.yaml") << "gazebo_ros_control: [unclosed\n";
  const std::string url = lcm_control::testing::unique_lcm_url();
  struct Case {
    std::vector<std::string> args;
    std::string mentions;
  } cases[] = {
      {{"--urdf", dir + "/broken.urdf"}, "broken.urdf"},
      {{"--urdf", dir + "/missing.urdf"}, "missing.urdf"},
      {{"--urdf", kTurretUrdf, "--config", dir + "/broken.yaml"}, "broken.yaml"},
      {{"--urdf", kTurretUrdf, "--physics-rate", "1000", "--control-rate", "300"}, "--control-rate"},
  };
  for (const Case& c : cases) {
    std::vector<std::string> argv{bin("sim_server"), "--lcm-url", url};
    argv.insert(argv.end(), c.args.begin(), c.args.end());
    ChildProcess p(argv);
    const int rc = p.wait(10.0);
    EXPECT_NE(rc, 0);
    EXPECT_NE(rc, -1);
    const auto out = lines(p.output());
    ASSERT_EQ(out.size(), 1u) << p.output();
    EXPECT_EQ(out[0].rfind("sim_server: error: ", 0), 0u) << out[0];
    EXPECT_NE(out[0].find(c.mentions), std::string::npos) << out[0];
  }
}

}  // namespace
}  // namespace lcm_control::sim::testing

namespace lcm_control::sim::testing {
namespace {

// switch_arm with j2 (a pitch joint, under gravity) effort-first and, when `hold` is false,
// <hold_joints>false</hold_joints> in the gz_ros2_control plugin tag.
std::string limp_arm(bool hold) {
  std::ifstream in(source("test/robots/switch_arm.urdf"));
  std::string urdf((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string j2 = "<joint name=\"j2\">\n      <command_interface name=\"position\"/>";
  urdf.replace(urdf.find(j2), j2.size(), "<joint name=\"j2\">\n      <command_interface name=\"effort\"/>");
  const std::string params = "<parameters>switch_arm.yaml</parameters>";
  if (!hold) urdf.replace(urdf.find(params), params.size(), params + "<hold_joints>false</hold_joints>");
  const std::string path = lcm_control::testing::temp_dir("hold_joints") + (hold ? "/held.urdf" : "/limp.urdf");
  std::ofstream(path) << urdf;
  return path;
}

// Where j2 is after a second of nobody commanding it.
double j2_after_a_second_uncommanded(bool hold, std::string* out) {
  SimServerProcess server;
  std::string why;
  if (!server.start({"--mode", "lockstep", "--lockstep-timeout", "0.1", "-J", "j2=0.5"}, limp_arm(hold), "", &why)) {
    *out = why;
    return NAN;
  }
  FakeController cm(server.lc);
  cm.policy = [](const hardware_state_t&, hardware_command_t& c) {
    for (auto& m : c.mode) m = hardware_command_t::MODE_NONE;
  };
  if (!cm.run_until_step(1000, 20.0)) {
    *out = server.output();
    return NAN;
  }
  *out = server.output();
  return cm.states.back().position[1];
}

TEST(sim_e2e, HoldJointsFalseLeavesAnUncommandedEffortJointLimpAndSaysSo) {
  std::string held_out, limp_out;
  const double held = j2_after_a_second_uncommanded(true, &held_out);
  const double limp = j2_after_a_second_uncommanded(false, &limp_out);
  EXPECT_NEAR(held, 0.5, 1e-3) << held_out;  // hold_joints' default: braked where it is
  EXPECT_GT(std::abs(limp - 0.5), 0.1) << limp_out;  // gravity takes it
  EXPECT_NE(limp_out.find("<hold_joints>false</hold_joints>: joints nobody commands are not braked"),
            std::string::npos)
      << limp_out;
  EXPECT_EQ(held_out.find("<hold_joints>"), std::string::npos) << held_out;
}

}  // namespace
}  // namespace lcm_control::sim::testing
