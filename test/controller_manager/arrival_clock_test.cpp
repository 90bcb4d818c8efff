// common/arrival_clock: the prediction a spinning receiver sleeps to.
#include <gtest/gtest.h>

#include "controller_manager/arrival_clock.hpp"

using namespace lcm_control;

TEST(ArrivalClock, NothingIsPredictedWithoutAPeriod) {
  ArrivalClock c;
  EXPECT_EQ(c.next_us(), -1);
  c.arrived(1000, 0);  // lockstep
  EXPECT_EQ(c.next_us(), -1);
  c.arrived(1000, 1000);
  EXPECT_EQ(c.next_us(), 2000);
  c.arrived(2000, 0);  // the sender went to lockstep
  EXPECT_EQ(c.next_us(), -1);
}

TEST(ArrivalClock, SettlesOnTheEarliestArrivalsOfAScheduleWithDelays) {
  ArrivalClock c;
  // A 1 ms schedule from 0, each arrival late by 20..80 us, one in ten on time.
  for (int64_t k = 0; k < 200; ++k) c.arrived(k * 1000 + (k % 10 == 0 ? 0 : 20 + (k * 37) % 61), 1000);
  const int64_t next = c.next_us() - 200 * 1000;  // how late of the schedule the prediction sits
  EXPECT_GE(next, 0);
  EXPECT_LE(next, 20);
  c.arrived(200 * 1000 + 3, 1000);  // early of the prediction: taken as it is
  EXPECT_EQ(c.next_us(), 201 * 1000 + 3);
}

TEST(ArrivalClock, FollowsASlowerSenderAndStartsOverAfterAStall) {
  ArrivalClock c;
  int64_t t = 0;
  for (int k = 0; k < 2000; ++k) c.arrived(t += 1001, 1000);  // the sender's clock runs 0.1 % slow
  EXPECT_NEAR(double(c.next_us() - t), 1000.0, 40.0);  // early of it by less than a period's drift times 32
  c.arrived(t += 25000, 1000);  // a 25 ms stall
  EXPECT_EQ(c.next_us(), t + 1000);
  c.arrived(t += 1000, 2000);  // a new period
  EXPECT_EQ(c.next_us(), t + 2000);
}

TEST(ArrivalClock, ASpinningReceiverSleepsToSpinBeforeTheArrivalAndNotAfterItsWindow) {
  ArrivalClock c;
  EXPECT_EQ(c.sleep_us(0, 100, 20000), 20000);  // nothing expected
  c.arrived(1000, 1000);                        // the next at 2000
  EXPECT_EQ(c.sleep_us(1100, 100, 20000), 800);  // to 1900
  EXPECT_EQ(c.sleep_us(1100, 100, 500), 500);
  EXPECT_EQ(c.sleep_us(1900, 100, 20000), 0);  // spinning from 1900 ...
  EXPECT_EQ(c.sleep_us(2099, 100, 20000), 0);
  EXPECT_EQ(c.sleep_us(2100, 100, 20000), 20000);  // ... to 2100: late, it sleeps until a message wakes it
  EXPECT_EQ(c.sleep_us(1100, 0, 20000), 20000);    // no spinning
}
