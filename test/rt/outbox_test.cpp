// The Outbox: messages leave from its own thread in the order committed, or from the
// caller's when it sends them itself; a full ring drops and counts without waiting
// for the sending thread; slots grow off the loop's thread.
#include "rt/outbox.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
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

TEST(Outbox, SentHereMessagesLeaveOnTheCallersThreadAndTheThreadSendsWhatIsLeft) {
  Received r;
  auto record = [&](const Outbox::Slot& s) {
    std::lock_guard<std::mutex> l(r.m);
    r.payloads.emplace_back(reinterpret_cast<const char*>(s.bytes.data()), s.size);
    r.threads.push_back(std::this_thread::get_id());
  };
  Outbox box(record, 8, 16);
  box.send_here(true);
  // As a lockstep loop uses it: commit, then send what is queued once the peer has its answer.
  for (int k = 0; k < 1000; ++k) {
    put(box, "c", std::to_string(k));
    box.send_queued();
    std::this_thread::sleep_for(std::chrono::microseconds(100));
  }
  {
    std::lock_guard<std::mutex> l(r.m);
    ASSERT_EQ(r.payloads.size(), 1000u);
    int here = 0;
    for (size_t k = 0; k < 1000; ++k) {
      EXPECT_EQ(r.payloads[k], std::to_string(k));
      here += r.threads[k] == std::this_thread::get_id();
    }
    // The thread, not woken by a commit, only takes one when its 100 ms fallback falls between commit and send.
    EXPECT_GE(here, 995);
  }
  // Left unsent, a message still leaves: from the thread, within its fallback period.
  put(box, "c", "left");
  const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (box.sent() < 1001 && std::chrono::steady_clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(box.sent(), 1001);
  {
    std::lock_guard<std::mutex> l(r.m);
    EXPECT_EQ(r.payloads.back(), "left");
    EXPECT_NE(r.threads.back(), std::this_thread::get_id());
  }
  // Off again: each commit wakes the thread (flush only waits for it then; 200 of them take far less than the
  // thread's 100 ms fallback would).
  box.send_here(false);
  const auto off = std::chrono::steady_clock::now();
  for (int k = 0; k < 200; ++k) {
    put(box, "c", "t" + std::to_string(k));
    box.flush();
  }
  EXPECT_LT(std::chrono::steady_clock::now() - off, std::chrono::seconds(5));
  std::lock_guard<std::mutex> l(r.m);
  ASSERT_EQ(r.payloads.size(), 1201u);
  for (size_t k = 1001; k < 1201; ++k) {
    EXPECT_EQ(r.payloads[k], "t" + std::to_string(k - 1001));
    EXPECT_NE(r.threads[k], std::this_thread::get_id());
  }
}

TEST(Outbox, TheCallerAndTheThreadNeverSendTheSameMessageOrOutOfOrder) {
  std::vector<int> got;  // only the sender holding the outbox's turn appends
  std::atomic<int> senders{0}, overlaps{0};
  Outbox box(
      [&](const Outbox::Slot& s) {
        if (senders.fetch_add(1) != 0) ++overlaps;
        got.push_back(std::stoi(std::string(reinterpret_cast<const char*>(s.bytes.data()), s.size)));
        senders.fetch_sub(1);
      },
      16, 16);
  int committed = 0;
  for (int k = 0; k < 20000; ++k) {
    box.send_here(k / 500 % 2 == 0);  // switched back and forth, so both send while the other may
    Outbox::Slot* s = box.begin();
    if (s) {
      const std::string p = std::to_string(committed);
      std::memcpy(s->bytes.data(), p.data(), p.size());
      s->channel = "c";
      s->size = p.size();
      box.commit();
      ++committed;
    }
    if (k % 3 == 0) box.send_queued();
  }
  box.send_here(false);
  box.flush();
  EXPECT_EQ(overlaps.load(), 0);
  ASSERT_EQ(got.size(), size_t(committed));
  for (int k = 0; k < committed; ++k) ASSERT_EQ(got[size_t(k)], k);
}
