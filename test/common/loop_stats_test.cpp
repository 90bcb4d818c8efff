// common/loop_stats: one statistics window of a loop, as both ends of the hardware loop publish it.
#include <gtest/gtest.h>

#include "common/loop_stats.hpp"

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
