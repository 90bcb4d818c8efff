// Goals within the limit, end to end (issue 51): turret_bot's trajectory controller at 1 kHz real time while
// 100,000-point goals arrive four a second. Its own binary, run alone (RUN_SERIAL): what it measures is the loop's
// regularity, which a test running beside it on a 2-core machine would disturb as much as a stalled loop would.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <vector>

#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "test/e2e/session.hpp"
#include "test/reliability/limits/goals.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;


// Goals within the limit are taken in off the loop (decoded and planned on the controller manager's intake thread,
// their fragments read a slice at a time): four 100,000-point goals a second (3.6 MB each) for 3 s leave the
// hardware commands regular (before: 39 gaps over 20 ms in 10 s, the longest 94 ms).
TEST(Limits, LargeGoalsWithinTheLimitDoNotStallTheLoop) {
  // A receive buffer that holds a whole goal (capped by net.core.rmem_max, which scripts/setup raises to 8 MiB).
  lt::RobotSession robot(lt::source("config/turret_bot.urdf"), lt::source("config/turret_bot_trajectory.yaml"),
                         lt::unique_lcm_url() + "&recv_buf_size=8388608");
  robot.start_controller_manager();
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_controller", "trajectory_controller"}));
  ASSERT_NO_FATAL_FAILURE(robot.start_sim({}, 20));
  lcm::LCM lc(robot.url());
  lt::Recorder<hardware_command_t> commands(lc, "hardware/command");
  lt::Recorder<trajectory_status_t> feedback(lc, "trajectory_controller/feedback");
  ASSERT_TRUE(lt::pump_until(lc, [&] { return commands.messages.size() > 300; }, 20)) << robot.cm_output();
  auto gaps = [&](size_t from, double* longest_ms) {
    int over = 0;
    *longest_ms = 0;
    for (size_t k = from + 1; k < commands.arrival_us.size(); ++k) {
      const double ms = (commands.arrival_us[k] - commands.arrival_us[k - 1]) * 1e-3;
      *longest_ms = std::max(*longest_ms, ms);
      over += ms > 20;
    }
    return over;
  };
  const size_t quiet0 = commands.arrival_us.size();
  lt::pump_until(lc, [] { return false; }, 1.0);
  double quiet_ms = 0;
  const int quiet_over = gaps(quiet0, &quiet_ms);

  // Encoded before the window, so that this process only sends during it.
  std::vector<std::vector<uint8_t>> goals;
  for (int k = 0; k < 12; ++k) {
    const joint_trajectory_t g = lt::goal_of(9000 + k, 100000, [](int i) {
      return std::array<double, 2>{0.3 + 0.1 * std::sin(i * 1e-3), 0.2};
    });
    goals.emplace_back(size_t(g.getEncodedSize()));
    g.encode(goals.back().data(), 0, int(goals.back().size()));
  }
  const size_t busy0 = commands.arrival_us.size();
  int sent = 0;
  for (const auto& bytes : goals) {
    sent += lc.publish("trajectory_controller/command", bytes.data(), unsigned(bytes.size())) == 0;
    lt::pump_until(lc, [] { return false; }, 0.25);
  }
  lt::pump_until(lc, [] { return false; }, 0.5);
  double busy_ms = 0;
  const int busy_over = gaps(busy0, &busy_ms);
  std::set<int64_t> taken;
  for (const auto& f : feedback.messages)
    if (f.goal_id >= 9000) taken.insert(f.goal_id);
  // Taken in the loop, each of these goals held it 51-84 ms (12 gaps over 50 ms here). Off the loop a gap of 20-40
  // ms is still seen once or twice a run on this 2-core machine, soon after the first goals (its cause is not found
  // yet; the loop's own reads are bounded), never one of 50.
  EXPECT_LE(busy_over, 3) << "longest gap " << busy_ms << " ms";
  EXPECT_LT(busy_ms, 50.0);
  EXPECT_GE(taken.size(), 6u) << robot.cm_output();
  const std::string out = robot.cm_output();
  EXPECT_NE(out.find("goal 9011 accepted: 100000 points"), std::string::npos) << out.substr(out.size() - 3000);
  std::printf("RELIABILITY|limits|12 trajectory goals of 100,000 points (3.6 MB), 4 a second, at 1 kHz real time|"
              "tried=%d|ok=%zu|crashes=0|hangs=0|hardware commands: %d gaps over 20 ms, longest %.2f ms (without "
              "goals, 1 s: %d, %.2f ms); %zu goals followed\n",
              sent, taken.size(), busy_over, busy_ms, quiet_over, quiet_ms, taken.size());
}
