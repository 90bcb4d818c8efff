#include "dashboard/throttle.hpp"

#include <gtest/gtest.h>

namespace lcm_control::dashboard {
namespace {

void offer(Throttle& t, const std::string& channel, uint8_t byte, int64_t now_us, bool from_others = true) {
  t.offer(channel, &byte, 1, now_us, from_others);
}

TEST(Throttle, LatestWinsAndEachChannelGoesAtMostOncePerPeriod) {
  Throttle t(33333);
  for (int k = 0; k < 40; ++k) offer(t, "hardware/state", uint8_t(k), k * 1000);  // 1 kHz
  offer(t, "joint_states", 7, 39500);
  auto due = t.take_due(40000);
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(due[0].channel, "hardware/state");
  EXPECT_EQ(due[0].bytes, std::vector<uint8_t>{39});  // the newest
  EXPECT_EQ(due[0].skipped, 39);
  EXPECT_EQ(due[0].received_us, 39000);
  EXPECT_EQ(due[1].channel, "joint_states");

  offer(t, "hardware/state", 41, 41000);
  EXPECT_TRUE(t.take_due(50000).empty());  // within the period of the last hand-out
  due = t.take_due(73333);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0].bytes, std::vector<uint8_t>{41});
  EXPECT_EQ(due[0].skipped, 0);
  EXPECT_TRUE(t.take_due(200000).empty());  // nothing new: nothing again
}

TEST(Throttle, RatesOverTheLastSecondAndSilenceCountsOnlyOthers) {
  Throttle t(1000);
  EXPECT_EQ(t.last_message_us(), -1);
  for (int k = 0; k <= 1000; ++k) offer(t, "hardware/state", 0, k * 1000);
  offer(t, "controller_manager/request", 0, 1500000, false);  // the dashboard's own request
  auto rates = t.rates(1500000);
  ASSERT_EQ(rates.size(), 2u);
  EXPECT_EQ(rates[1].channel, "hardware/state");
  EXPECT_NEAR(rates[1].hz, 1000, 2);
  EXPECT_EQ(rates[1].total, 1001);
  EXPECT_EQ(t.last_message_us(), 1000000);  // its own echo does not make the bus alive
  // A channel that went quiet reads 0 Hz once a whole second has passed without it.
  rates = t.rates(5000000);
  EXPECT_EQ(rates[1].hz, 0);
}

TEST(Throttle, AFloodOfInventedChannelNamesIsCountedNotKept) {
  Throttle t(1000);
  for (size_t k = 0; k < Throttle::kMaxChannels + 500; ++k) offer(t, "junk/" + std::to_string(k), 1, int64_t(k));
  EXPECT_EQ(t.rates(2000).size(), Throttle::kMaxChannels);
  EXPECT_EQ(t.ignored(), 500);
  EXPECT_EQ(t.last_message_us(), int64_t(Throttle::kMaxChannels + 499));  // still a sign of life
  offer(t, "junk/0", 2, 5000);  // a channel already kept goes on
  EXPECT_EQ(t.take_due(6000).size(), Throttle::kMaxChannels);
}

}  // namespace
}  // namespace lcm_control::dashboard
