#include "rt/byte_pool.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <thread>

namespace lcm_control {
namespace {

std::vector<uint8_t> room(size_t capacity) {
  std::vector<uint8_t> v;
  v.reserve(capacity);
  v.resize(capacity / 2, 7);
  return v;
}

// Two slots keep the two largest rooms given back, emptied; take() hands out the smallest that holds the size asked,
// the very buffer given back, and nothing when none does.
TEST(BytePool, KeepsTheLargestRoomsAndHandsOutTheSmallestThatFits) {
  BytePool pool(2);
  std::vector<uint8_t> a = room(1000), b = room(3000), c = room(2000);
  const uint8_t* b_at = b.data();
  const uint8_t* c_at = c.data();
  pool.give_back(std::move(a));
  pool.give_back(std::move(b));
  pool.give_back(std::move(c));  // replaces the 1000
  EXPECT_EQ(pool.kept_bytes(), 5000u);
  EXPECT_EQ(pool.take(4000).capacity(), 0u) << "none holds 4000";
  std::vector<uint8_t> got = pool.take(1500);
  EXPECT_EQ(got.data(), c_at) << "the 2000, not the 3000";
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(pool.take(1500).data(), b_at);
  EXPECT_EQ(pool.kept_bytes(), 0u);
  std::vector<uint8_t> small = room(10);
  pool.give_back(std::move(small));
  pool.give_back(room(20));
  pool.give_back(room(5));  // smaller than both kept: freed
  EXPECT_EQ(pool.kept_bytes(), 30u);
}

// offer() is give_back() for the loop's side: it takes the bytes (the room they replace freed in it); a room
// smaller than every kept one is freed as well. Rooms given back from another thread while the loop's side takes:
// each take is none or a room that holds what was asked.
TEST(BytePool, OfferTakesTheBytesAndGiversOnOtherThreadsAreSafe) {
  BytePool pool(1);
  std::vector<uint8_t> mine = room(500);
  EXPECT_TRUE(pool.offer(mine));
  EXPECT_EQ(mine.capacity(), 0u);
  EXPECT_EQ(pool.kept_bytes(), 500u);
  std::thread giver([&] {
    for (int k = 0; k < 20000; ++k) pool.give_back(room(1000 + size_t(k % 7) * 100));
  });
  int taken = 0;
  for (int k = 0; k < 20000; ++k) {
    std::vector<uint8_t> got = pool.take(1200);
    if (got.capacity() > 0) {
      ++taken;
      EXPECT_GE(got.capacity(), 1200u);
      EXPECT_TRUE(got.empty());
    }
  }
  giver.join();
  std::printf("%d of 20000 takes found a room\n", taken);
}

}  // namespace
}  // namespace lcm_control
