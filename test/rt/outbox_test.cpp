// The Outbox: messages leave from its own thread in the order committed; a full
// ring drops and counts without waiting for the sending thread; slots grow off
// the loop's thread.
#include "rt/outbox.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

using lcm_control::Outbox;

namespace {

struct Received {
  std::mutex m;
  std::vector<std::string> channels;
  std::vector<std::string> payloads;
  std::vector<std::thread::id> threads;
  std::vector<size_t> room;  // each slot's bytes.size() when sent
};

void put(Outbox& box, const std::string& channel, const std::string& payload) {
  Outbox::Slot* s = box.begin();
  ASSERT_NE(s, nullptr);
  if (s->bytes.size() < payload.size()) s->bytes.resize(payload.size());
  std::memcpy(s->bytes.data(), payload.data(), payload.size());
  s->channel = channel;
  s->size = payload.size();
  box.commit();
}

}  // namespace

TEST(Outbox, SendsFromItsOwnThreadInTheOrderCommitted) {
  Received r;
  {
    Outbox box(
        [&](const Outbox::Slot& s) {
          std::lock_guard<std::mutex> l(r.m);
          r.channels.push_back(s.channel);
          r.payloads.emplace_back(reinterpret_cast<const char*>(s.bytes.data()), s.size);
          r.threads.push_back(std::this_thread::get_id());
        },
        8, 16);
    for (int k = 0; k < 2000; ++k) {
      // A producer faster than the sender gets nullptr when the ring is full; retry after a pause.
      while (box.dropped() < 100000) {
        Outbox::Slot* s = box.begin();
        if (!s) {
          std::this_thread::yield();
          continue;
        }
        const std::string p = "message " + std::to_string(k);
        if (s->bytes.size() < p.size()) s->bytes.resize(p.size());
        std::memcpy(s->bytes.data(), p.data(), p.size());
        s->channel = k % 2 ? "odd" : "even";
        s->size = p.size();
        box.commit();
        break;
      }
    }
    box.flush();
    EXPECT_EQ(box.sent(), 2000);
  }
  ASSERT_EQ(r.payloads.size(), 2000u);
  for (int k = 0; k < 2000; ++k) {
    EXPECT_EQ(r.payloads[size_t(k)], "message " + std::to_string(k));
    EXPECT_EQ(r.channels[size_t(k)], k % 2 ? "odd" : "even");
    EXPECT_NE(r.threads[size_t(k)], std::this_thread::get_id());
  }
}

TEST(Outbox, AFullRingDropsAndCountsWithoutWaitingForTheSender) {
  std::mutex m;
  std::condition_variable cv;
  bool release = false;
  int sent = 0;
  Outbox box(
      [&](const Outbox::Slot&) {
        std::unique_lock<std::mutex> l(m);
        cv.wait(l, [&] { return release; });  // a socket that does not drain
        ++sent;
      },
      4, 64);
  for (int k = 0; k < 4; ++k) put(box, "c", "x");
  // The sender holds the first slot inside send and the ring is full: these return at once, counted.
  for (int k = 0; k < 10; ++k) EXPECT_EQ(box.begin(), nullptr);
  EXPECT_EQ(box.dropped(), 10);
  {
    std::lock_guard<std::mutex> l(m);
    release = true;
  }
  cv.notify_all();
  box.flush();
  EXPECT_EQ(sent, 4);
  EXPECT_EQ(box.sent(), 4);
  put(box, "c", "after");  // room again
  box.flush();
  EXPECT_EQ(box.sent(), 5);
}

TEST(Outbox, ASecondThreadHandingOverAtTheSameMomentIsDroppedNotWaitedFor) {
  Outbox box([](const Outbox::Slot&) {}, 4, 64);
  Outbox::Slot* s = box.begin();
  ASSERT_NE(s, nullptr);
  Outbox::Slot* other = s;
  std::thread([&] { other = box.begin(); }).join();
  EXPECT_EQ(other, nullptr);
  EXPECT_EQ(box.dropped(), 1);
  box.abandon();
  EXPECT_NE(box.begin(), nullptr);
  box.abandon();
  box.flush();
  EXPECT_EQ(box.sent(), 0);
}

TEST(Outbox, TheSenderGrowsEverySlotItFreesToTheLargestMessage) {
  Received r;
  Outbox box(
      [&](const Outbox::Slot& s) {
        std::lock_guard<std::mutex> l(r.m);
        r.room.push_back(s.bytes.size());
      },
      4, 16);
  put(box, "big", std::string(1000, 'b'));  // slot 0 grown by the producer
  box.flush();
  for (int k = 0; k < 4; ++k) {  // slots 1, 2, 3, 0: small messages, in slots still 16 bytes (1-3)
    Outbox::Slot* s = box.begin();
    ASSERT_NE(s, nullptr);
    s->channel = "small";
    s->size = 1;
    box.commit();
  }
  box.flush();
  // Every slot the sender has freed since the big message is now at least as big: the producer's next lap needs
  // no allocation.
  for (int k = 0; k < 4; ++k) {
    Outbox::Slot* s = box.begin();
    ASSERT_NE(s, nullptr);
    EXPECT_GE(s->bytes.size(), 1000u) << "slot " << k;
    s->size = 1;
    box.commit();
  }
  box.flush();
}
