// common/loop_stats: one statistics window of a loop, as both ends of the hardware loop publish it.
#include <gtest/gtest.h>

#include "rt/loop_stats.hpp"

using namespace lcm_control;

TEST(LoopStats, PeriodsWorkOverrunsAndAFreshWindowThatKeepsTheLastStart) {
  LoopStats s;
  s.add_cycle(1000, 100, false);
  s.add_cycle(2000, 300, false);
  s.add_cycle(4000, 1200, true);  // a late one, by the caller's rule
  s.add_missed(2);
  s.add_dropped(3);
  s.set_real_time_factor(0.98);
  loop_stats_t m{};
  s.fill_and_reset(m);
  EXPECT_EQ(m.cycles, 3);
  EXPECT_DOUBLE_EQ(m.period_mean_us, 1500);  // 1000 and 2000
  EXPECT_DOUBLE_EQ(m.period_min_us, 1000);
  EXPECT_DOUBLE_EQ(m.period_max_us, 2000);
  EXPECT_DOUBLE_EQ(m.period_jitter_us, 500);
  EXPECT_EQ(m.overruns, 1);
  EXPECT_EQ(m.missed, 2);
  EXPECT_EQ(m.dropped, 3);
  EXPECT_DOUBLE_EQ(m.real_time_factor, 0.98);
  EXPECT_DOUBLE_EQ(m.exec_mean_us, 1600.0 / 3);  // 100, 300, 1200
  EXPECT_DOUBLE_EQ(m.exec_max_us, 1200);

  s.add_cycle(5000, 10, false);  // the period from the last window's last start
  s.fill_and_reset(m);
  EXPECT_EQ(m.cycles, 1);
  EXPECT_DOUBLE_EQ(m.period_mean_us, 1000);
  EXPECT_EQ(m.overruns, 0);
  EXPECT_EQ(m.missed, 0);
}

TEST(LoopStats, PeriodErrorPercentilesAgainstTheNominalPeriodInRealTimeOnly) {
  LoopStats s;
  loop_stats_t m{};
  s.add_cycle(0, 1, false);
  s.add_cycle(1500, 1, false);
  s.fill_and_reset(m);
  EXPECT_EQ(m.period_error_p50_us, 0);  // no nominal period (lockstep): none taken
  EXPECT_EQ(m.period_error_p99_us, 0);

  s.set_nominal_period_us(1000);
  int64_t t = 1500;
  for (int k = 1; k <= 200; ++k) s.add_cycle(t += (k % 100 == 0 ? 1400 : 1000 + (k % 2 ? 10 : -10)), 1, false);
  s.fill_and_reset(m);
  EXPECT_DOUBLE_EQ(m.period_error_p50_us, 10);  // 198 periods 10 us off, 2 of them 400 us
  EXPECT_DOUBLE_EQ(m.period_error_p99_us, 10);  // the 198th of 200
  for (int k = 1; k <= 100; ++k) s.add_cycle(t += (k % 10 == 0 ? 1400 : 1000), 1, false);
  s.fill_and_reset(m);  // a fresh window: 90 on time, 10 of them 400 us late
  EXPECT_DOUBLE_EQ(m.period_error_p50_us, 0);
  EXPECT_DOUBLE_EQ(m.period_error_p99_us, 400);
  EXPECT_EQ(m.cycles, 100);
}

TEST(LoopStats, AWindowLongerThanTheBufferKeepsItsFirstErrors) {
  LoopStats s;
  s.set_nominal_period_us(100);
  int64_t t = 0;
  s.add_cycle(t, 1, false);
  for (size_t k = 0; k < LoopStats::kErrorCapacity; ++k) s.add_cycle(t += 101, 1, false);
  for (int k = 0; k < 1000; ++k) s.add_cycle(t += 500, 1, false);  // past the buffer: not counted
  loop_stats_t m{};
  s.fill_and_reset(m);
  EXPECT_DOUBLE_EQ(m.period_error_p99_us, 1);
  EXPECT_EQ(m.cycles, int64_t(LoopStats::kErrorCapacity) + 1001);
}

TEST(ExecStats, PercentilesComeWithinTheHistogramsTwoPercent) {
  ExecStats e;
  EXPECT_EQ(e.percentile_us(0.99), 0.0) << "empty";
  for (int k = 1; k <= 1000; ++k) e.add(double(k));
  EXPECT_NEAR(e.percentile_us(0.99), 990.0, 0.02 * 990.0);
  EXPECT_NEAR(e.percentile_us(0.5), 500.0, 0.02 * 500.0);
  EXPECT_DOUBLE_EQ(e.percentile_us(1.0), 1000.0) << "never above the max";
  EXPECT_DOUBLE_EQ(e.mean_us(), 500.5);
  e.reset();
  e.add(200.0);
  EXPECT_DOUBLE_EQ(e.percentile_us(0.99), 200.0);
  e.add(0.0);    // below the lowest bin
  e.add(1e12);   // above the highest
  EXPECT_EQ(e.n, 3);
  EXPECT_DOUBLE_EQ(e.percentile_us(1.0), 1e12);
}

TEST(ExecStats, AddItemFillsEveryPerItemArrayAndStartsANewWindow) {
  ExecStats exec, period;
  for (int k = 0; k < 10; ++k) {
    exec.add(100);
    period.add(1000);
  }
  loop_stats_t m{};
  add_item(m, "arm_controller", "controller", exec, &period);
  add_item(m, "step", "stage", exec, nullptr);
  ASSERT_EQ(m.num_items, 2);
  EXPECT_EQ(m.item_kind, (std::vector<std::string>{"controller", "stage"}));
  EXPECT_EQ(m.item_count, (std::vector<int64_t>{10, 0}));
  EXPECT_DOUBLE_EQ(m.item_exec_mean_us[0], 100);
  EXPECT_DOUBLE_EQ(m.item_exec_p99_us[0], 100);
  EXPECT_DOUBLE_EQ(m.item_period_mean_us[0], 1000);
  EXPECT_DOUBLE_EQ(m.item_period_max_us[0], 1000);
  EXPECT_DOUBLE_EQ(m.item_period_p99_us[1], 0);
  EXPECT_EQ(period.n, 0);
}
