#include "rt/intake.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <string>
#include <thread>
#include <vector>

using namespace lcm_control;

namespace {

void wait_until(const std::function<bool()>& done) {
  for (int k = 0; k < 10000 && !done(); ++k) std::this_thread::sleep_for(std::chrono::milliseconds(1));
}

}  // namespace

// The jobs run on the intake's thread, their results only when the loop drains, in the order submitted, however
// long each job took.
TEST(Intake, ResultsRunOnTheLoopsThreadAtDrainInTheOrderSubmitted) {
  Intake intake;
  const auto loop = std::this_thread::get_id();
  std::vector<std::thread::id> job_threads;
  std::vector<int> taken;
  for (int k = 0; k < 5; ++k)
    intake.submit([&, k]() -> Intake::Result {
      job_threads.push_back(std::this_thread::get_id());
      std::this_thread::sleep_for(std::chrono::milliseconds(k == 0 ? 30 : 1));
      return [&, k] {
        EXPECT_EQ(std::this_thread::get_id(), loop);
        taken.push_back(k);
      };
    });
  EXPECT_TRUE(intake.busy());
  wait_until([&] { return intake.done() == 5; });
  EXPECT_TRUE(taken.empty()) << "nothing is taken before drain()";
  EXPECT_TRUE(intake.busy()) << "results wait to be taken";
  EXPECT_EQ(intake.drain(), 5u);
  EXPECT_EQ(taken, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_FALSE(intake.busy());
  for (const auto& id : job_threads) EXPECT_NE(id, loop);
}

// In place (lockstep), a job and its result run in submit(), after what was submitted before has been taken.
TEST(Intake, InPlaceRunsAtOnceAfterWhatCameBefore) {
  Intake intake;
  std::vector<std::string> order;
  intake.submit([&]() -> Intake::Result {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    return [&] { order.push_back("earlier"); };
  });
  intake.set_in_place(true);
  intake.submit([&]() -> Intake::Result { return [&] { order.push_back("in place"); }; });
  EXPECT_EQ(order, (std::vector<std::string>{"earlier", "in place"}));
  EXPECT_EQ(intake.drain(), 0u);
  EXPECT_FALSE(intake.busy());
}

// What the loop gives up is freed on the intake's thread, in place or not.
TEST(Intake, DisposeFreesOnItsThread) {
  struct Tracked {
    std::atomic<std::thread::id>* freed_on;
    bool live = true;
    explicit Tracked(std::atomic<std::thread::id>* f) : freed_on(f) {}
    Tracked(Tracked&& o) noexcept : freed_on(o.freed_on) { o.live = false; }
    ~Tracked() {
      if (live) *freed_on = std::this_thread::get_id();
    }
  };
  std::atomic<std::thread::id> freed_on{};
  Intake intake;
  intake.set_in_place(true);
  intake.dispose(Tracked(&freed_on));
  wait_until([&] { return freed_on.load() != std::thread::id(); });
  EXPECT_NE(freed_on.load(), std::thread::id());
  EXPECT_NE(freed_on.load(), std::this_thread::get_id());
}

// Destroyed with work left: the jobs not started are dropped, and no result runs.
TEST(Intake, DestroyedWithWorkLeftDropsItQuietly) {
  std::atomic<int> ran{0};
  bool taken = false;
  {
    Intake intake;
    for (int k = 0; k < 100; ++k)
      intake.submit([&]() -> Intake::Result {
        ++ran;
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        return [&] { taken = true; };
      });
  }
  EXPECT_LT(ran.load(), 100);
  EXPECT_FALSE(taken);
}
