// turret-cmd against a subscriber on a private LCM URL: values, rate, message
// types, channel naming, errors, and sim-time pacing by a fake sim's hardware/state.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

TEST(TurretCmd, SineAt60HzMatchesTheFormulaAndTheRate) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_t> rec(lc, "j2_controller/command");
  ChildProcess p({bin("turret-cmd"), "j2_controller", "3.14*sin(i/100)", "--rate", "60", "--count", "120",
                  "--lcm-url", url});
  ASSERT_TRUE(pump_until(lc, [&] { return rec.messages.size() >= 120; }, 6.0)) << p.output();
  EXPECT_EQ(p.wait(3.0), 0) << p.output();
  pump_until(lc, [] { return false; }, 0.1);
  ASSERT_EQ(rec.messages.size(), 120u);
  for (size_t i = 0; i < rec.messages.size(); ++i)
    EXPECT_NEAR(rec.messages[i].data, 3.14 * std::sin(double(i) / 100.0), 1e-12) << "message " << i;
  // The rate, robust to a stall of a loaded machine: the median spacing of
  // arrivals and of the utime stamps (wall clock at sending) is 1/60 s.
  auto median_gap_s = [](std::vector<int64_t> t) {
    std::vector<double> gaps;
    for (size_t k = 1; k < t.size(); ++k) gaps.push_back(double(t[k] - t[k - 1]) * 1e-6);
    std::nth_element(gaps.begin(), gaps.begin() + long(gaps.size() / 2), gaps.end());
    return gaps[gaps.size() / 2];
  };
  std::vector<int64_t> stamps;
  for (const auto& m : rec.messages) stamps.push_back(m.utime);
  EXPECT_NEAR(median_gap_s(rec.receive_us), 1.0 / 60, 0.1 / 60);
  EXPECT_NEAR(median_gap_s(stamps), 1.0 / 60, 0.05 / 60);
  const double span_s = double(rec.receive_us.back() - rec.receive_us.front()) * 1e-6;
  std::printf("120 messages in %.3f s: %.2f Hz\n", span_s, 119.0 / span_s);
}

TEST(TurretCmd, OnceWithoutRate) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_t> rec(lc, "j1_controller/command");
  ChildProcess p({bin("turret-cmd"), "j1_controller", "0.5", "--lcm-url", url});
  EXPECT_EQ(p.wait(5.0), 0) << p.output();
  pump_until(lc, [&] { return !rec.messages.empty(); }, 2.0);
  ASSERT_EQ(rec.messages.size(), 1u);
  EXPECT_EQ(rec.messages[0].data, 0.5);
}

TEST(TurretCmd, SeveralExpressionsSendAnArrayOnARawChannelWithNamespace) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_array_t> rec(lc, "robot1/arm/goal");
  ChildProcess p({bin("turret-cmd"), "/arm/goal", "i", "2*t", "pi", "--rate", "100", "--count", "5", "--namespace",
                  "robot1", "--print", "--lcm-url", url});
  ASSERT_TRUE(pump_until(lc, [&] { return rec.messages.size() >= 5; }, 5.0)) << p.output();
  EXPECT_EQ(p.wait(3.0), 0);
  // --print shows "i t values" for each message; t is seconds since start (i/100 unless the machine stalled).
  std::vector<std::string> lines;
  for (const auto& l : split(p.output(), '\n'))
    if (!l.empty() && l.rfind("turret-cmd:", 0) != 0) lines.push_back(l);
  ASSERT_EQ(lines.size(), 5u) << p.output();
  for (size_t i = 0; i < 5; ++i) {
    ASSERT_EQ(rec.messages[i].size, 3);
    ASSERT_EQ(rec.messages[i].data.size(), 3u);
    EXPECT_EQ(rec.messages[i].data[0], double(i));
    const auto printed = split(lines.at(i), ' ');
    ASSERT_EQ(printed.size(), 5u) << lines[i];
    EXPECT_EQ(printed[0], std::to_string(i));
    const double t = std::stod(printed[1]);
    EXPECT_GE(t, 0.01 * double(i) - 1e-9);
    EXPECT_NEAR(rec.messages[i].data[1], 2.0 * t, 1e-5);
    EXPECT_NEAR(rec.messages[i].data[2], M_PI, 1e-12);
  }
}

TEST(TurretCmd, AsChannelFlagAndArrayFlag) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_array_t> rec(lc, "setpoint");
  ChildProcess p({bin("turret-cmd"), "setpoint", "7", "--as-channel", "--array", "--lcm-url", url});
  EXPECT_EQ(p.wait(5.0), 0) << p.output();
  ChildProcess old({bin("turret-cmd"), "setpoint", "8", "--channel", "--array", "--lcm-url", url});  // the old name
  EXPECT_EQ(old.wait(5.0), 0) << old.output();
  pump_until(lc, [&] { return rec.messages.size() >= 2; }, 2.0);
  ASSERT_EQ(rec.messages.size(), 2u);
  EXPECT_EQ(rec.messages[0].data, std::vector<double>{7.0});
  EXPECT_EQ(rec.messages[1].data, std::vector<double>{8.0});
  ChildProcess help({bin("turret-cmd"), "--help"});
  EXPECT_EQ(help.wait(5.0), 0);
  EXPECT_EQ(help.output().find("--channel"), std::string::npos) << "one meaning of --channel: a regex (bus record, "
                                                                    "log2csv)\n"
                                                 << help.output();
}

TEST(TurretCmd, BadExpressionFailsWithOneLine) {
  ChildProcess p({bin("turret-cmd"), "j2_controller", "3.14*sin(", "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(p.wait(5.0), 1);
  EXPECT_NE(p.output().find("turret-cmd: error: expression '3.14*sin('"), std::string::npos) << p.output();
}

TEST(TurretCmd, NanIsNeverSent) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_t> rec(lc, "j2_controller/command");
  ChildProcess p({bin("turret-cmd"), "j2_controller", "sqrt(2-i)", "--rate", "200", "--count", "10", "--lcm-url", url});
  EXPECT_EQ(p.wait(5.0), 1);
  pump_until(lc, [] { return false; }, 0.2);
  EXPECT_EQ(rec.messages.size(), 3u);
  EXPECT_NE(p.output().find("at i=3"), std::string::npos) << p.output();
}

// A controller TARGET on sim time asks the controller manager for a command source.
TEST(TurretCmd, SimTimeWithoutControllerManagerTimesOut) {
  ChildProcess p({bin("turret-cmd"), "j2_controller", "1", "--sim-time", "--timeout", "0.5", "--lcm-url",
                  unique_lcm_url()});
  EXPECT_EQ(p.wait(5.0), 4);  // kExitBus
  EXPECT_NE(p.output().find("no answer from the controller manager within 0.5 s to the command source for "
                            "'j2_controller'"),
            std::string::npos)
      << p.output();
}

TEST(TurretCmd, SimTimeWithoutHardwareStateTimesOut) {
  ChildProcess p({bin("turret-cmd"), "j2_controller/command", "1", "--sim-time", "--timeout", "0.5",
                  "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(p.wait(5.0), 1);
  EXPECT_NE(p.output().find("no hardware_state_t on 'hardware/state'"), std::string::npos) << p.output();
}

// A fake lockstep sim: publishes the state of step k and waits for the command due
// at step k+1 before it publishes state k+1, as the controller manager would read it.
TEST(TurretCmd, SimTimeSendsEachTickCommandBeforeTheTick) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_t> rec(lc, "j2_controller/command");
  ChildProcess p({bin("turret-cmd"), "j2_controller/command", "10*i + t", "--sim-time", "--count", "40", "--lcm-url",
                  url});
  const int64_t period_us = 1000, first_step = 500;
  hardware_state_t state{};
  // Until turret-cmd listens, the first states go unheard; start counting at its first answer.
  int64_t step = first_step;
  auto publish_state = [&](int64_t k) {
    state.step = k;
    state.utime = k * period_us;
    lc.publish("hardware/state", &state);
  };
  while (rec.messages.empty()) {
    ASSERT_LT(step, first_step + 200) << "turret-cmd never answered hardware/state\n" << p.output();
    publish_state(step);
    pump_until(lc, [&] { return !rec.messages.empty(); }, 0.05);
    if (rec.messages.empty()) ++step;
  }
  pump_until(lc, [] { return false; }, 0.1);
  // Message 0 is for the first step it heard, message 1 for the next one.
  const int64_t start = rec.messages[0].utime / period_us;
  ASSERT_EQ(int64_t(rec.messages.size()), step - start + 2) << p.output();
  for (int64_t k = step + 1; rec.messages.size() < 40; ++k) {
    ASSERT_LT(k, start + 40) << p.output();
    publish_state(k);
    const size_t want = size_t(k - start + 2);
    ASSERT_TRUE(pump_until(lc, [&] { return rec.messages.size() >= want; }, 2.0)) << "step " << k;
    EXPECT_EQ(rec.messages.size(), want);
  }
  EXPECT_EQ(p.wait(3.0), 0) << p.output();
  ASSERT_EQ(rec.messages.size(), 40u);
  for (size_t i = 0; i < rec.messages.size(); ++i) {
    EXPECT_NEAR(rec.messages[i].data, 10.0 * double(i) + double(i) * 1e-3, 1e-9) << i;
    EXPECT_EQ(rec.messages[i].utime, (start + int64_t(i)) * period_us) << i;
  }
}

TEST(TurretCmd, SimTimeRateIsInSimSeconds) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_t> rec(lc, "c/command");
  // 100 Hz of sim time on 1 kHz control steps: one message every 10 steps.
  ChildProcess p({bin("turret-cmd"), "c/command", "t", "--sim-time", "--rate", "100", "--duration", "0.05", "--lcm-url",
                  url});
  hardware_state_t state{};
  int64_t k = 1;
  while (rec.messages.empty() && k < 2000) {
    state.step = k;
    state.utime = k * 1000;
    lc.publish("hardware/state", &state);
    pump_until(lc, [&] { return !rec.messages.empty(); }, 0.01);
    ++k;
  }
  for (int n = 0; n < 60 && p.running(); ++n, ++k) {
    state.step = k;
    state.utime = k * 1000;
    lc.publish("hardware/state", &state);
    pump_until(lc, [] { return false; }, 0.005);
  }
  EXPECT_EQ(p.wait(3.0), 0) << p.output();
  pump_until(lc, [] { return false; }, 0.1);
  ASSERT_EQ(rec.messages.size(), 5u) << p.output();
  for (size_t i = 0; i < 5; ++i) EXPECT_NEAR(rec.messages[i].data, 0.01 * double(i), 1e-12);
  EXPECT_EQ(rec.messages[1].utime - rec.messages[0].utime, 10000);
}
