// One time base: commands from turret-cmd and bus pub carry sim time when
// sim_server's clock is on the bus, and tracking-summary and plotter refuse to
// join channels stamped on different clocks (issue 12, item 1).
#include <gtest/gtest.h>

#include <atomic>
#include <thread>

#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"
#include "tools/lib/clients/time_base.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

namespace {

constexpr int64_t kWallUtime = 1795000000000000;  // November 2026

// sim_server's `clock` at 100 Hz from sim time start_us on, 10 ms per message.
class FakeClock {
 public:
  FakeClock(const std::string& url, int64_t start_us) : lc_(url) {
    thread_ = std::thread([this, start_us] {
      sim_clock_t c{};
      c.utime = start_us;
      while (!stop_) {
        lc_.publish("clock", &c);
        c.utime += 10000;
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
      }
    });
  }
  ~FakeClock() {
    stop_ = true;
    thread_.join();
  }

 private:
  lcm::LCM lc_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

// joint_states in sim time (from 0, 100 Hz) and j2 commands stamped `command_utime0` + t.
void write_log(const std::string& path, int64_t command_utime0) {
  TestLog log(path);
  for (int k = 0; k < 50; ++k) {
    const int64_t t = k * 10000;
    joint_state_t js{};
    js.utime = t;
    js.num_joints = 1;
    js.name = {"j2"};
    js.position = {0.1};
    js.velocity = {0};
    js.effort = {0};
    log.put_message("joint_states", t, js);
    float64_t c{};
    c.utime = command_utime0 + t;
    c.data = 0.5;
    log.put_message("j2_controller/command", t + 100, c);
  }
}

}  // namespace

TEST(TimeBase, SimTimeAndWallClockAreTold) {
  using tools::TimeBase;
  EXPECT_EQ(tools::time_base(0), TimeBase::Sim);
  EXPECT_EQ(tools::time_base(int64_t(3600) * 24 * 365 * 1000000), TimeBase::Sim);  // a year of sim time
  EXPECT_EQ(tools::time_base(kWallUtime), TimeBase::Wall);
  EXPECT_EQ(tools::mixed_clocks("a", 5, "b", 7), "");
  EXPECT_NE(tools::mixed_clocks("joint_states", 5, "cmd", kWallUtime)
                .find("joint_states is stamped in sim time (utime 5) but cmd in wall-clock time"),
            std::string::npos);
}

TEST(TimeBase, TurretCmdAndBusPubStampSimTimeWhenTheSimClockIsOnTheBus) {
  const std::string url = unique_lcm_url();
  lcm::LCM lc(url);
  Recorder<float64_t> rec(lc, "j1_controller/command");
  {
    ChildProcess wall({bin("turret-cmd"), "j1_controller", "0.5", "--lcm-url", url});
    EXPECT_EQ(wall.wait(10), 0) << wall.output();
    ASSERT_TRUE(pump_until(lc, [&] { return rec.messages.size() == 1; }, 3));
    EXPECT_EQ(tools::time_base(rec.messages[0].utime), tools::TimeBase::Wall);  // no sim: the wall clock
  }
  FakeClock clock(url, 7000000);
  ChildProcess once({bin("turret-cmd"), "j1_controller", "0.5", "--lcm-url", url});
  EXPECT_EQ(once.wait(10), 0) << once.output();
  ChildProcess rated({bin("turret-cmd"), "j1_controller", "0.5", "--rate", "20", "--count", "10", "--lcm-url", url});
  EXPECT_EQ(rated.wait(10), 0) << rated.output();
  ChildProcess pub({bin("bus"), "pub", "j1_controller/command", "float64_t", "data=0.5", "--lcm-url", url});
  EXPECT_EQ(pub.wait(10), 0) << pub.output();
  EXPECT_NE(pub.output().find("stamped in sim time"), std::string::npos) << pub.output();
  ASSERT_TRUE(pump_until(lc, [&] { return rec.messages.size() == 13; }, 3));
  for (size_t k = 1; k < rec.messages.size(); ++k) {
    EXPECT_GE(rec.messages[k].utime, 7000000) << "message " << k;
    EXPECT_LT(rec.messages[k].utime, 7000000 + 60000000) << "message " << k;
  }
  // At 20 Hz for 10 messages (0.45 s) the sim clock (100 Hz here) moves on: the stamps are not all the same.
  EXPECT_GT(rec.messages[11].utime, rec.messages[2].utime);
}

TEST(TimeBase, TrackingSummaryRefusesMixedClocksAndJoinsByLogTimeOnRequest) {
  const std::string dir = temp_dir("time_base");
  write_log(dir + "/mixed.lcmlog", kWallUtime);
  ChildProcess mixed({bin("tracking-summary"), dir + "/mixed.lcmlog", "--joint", "j2=j2_controller/command"});
  EXPECT_EQ(mixed.wait(10), 3) << mixed.output();
  EXPECT_NE(mixed.output().find("joint_states is stamped in sim time (utime 0) but j2_controller/command in "
                                "wall-clock time"),
            std::string::npos)
      << mixed.output();
  EXPECT_NE(mixed.output().find("--time log"), std::string::npos) << mixed.output();

  ChildProcess by_log({bin("tracking-summary"), dir + "/mixed.lcmlog", "--joint", "j2=/j2_controller/command",
                       "--joint-states", "/joint_states", "--time", "log", "--no-timing"});  // ROS-style names too
  EXPECT_EQ(by_log.wait(10), 0) << by_log.output();
  EXPECT_NE(by_log.output().find("rms error 0.400000, max error 0.400000 (49 samples"), std::string::npos)
      << by_log.output();

  write_log(dir + "/late.lcmlog", 10000000);  // commands in sim time, but all after the last state
  ChildProcess late({bin("tracking-summary"), dir + "/late.lcmlog", "--joint", "j2=j2_controller/command"});
  EXPECT_EQ(late.wait(10), 3) << late.output();
  EXPECT_NE(late.output().find("came before the first command"), std::string::npos) << late.output();
}

TEST(TimeBase, PlotterRefusesToPlotMixedClocksAgainstUtime) {
  const std::string dir = temp_dir("time_base_plot");
  write_log(dir + "/mixed.lcmlog", kWallUtime);
  ChildProcess p({bin("plotter"), "joint_states.position[0]", "j2_controller/command", "--log", dir + "/mixed.lcmlog",
                  "--time", "utime", "--output", dir + "/p.png"});
  EXPECT_EQ(p.wait(20), 1) << p.output();
  EXPECT_NE(p.output().find("stamped in sim time"), std::string::npos) << p.output();
  ChildProcess ok({bin("plotter"), "joint_states.position[0]", "j2_controller/command", "--log", dir + "/mixed.lcmlog",
                   "--output", dir + "/p.png"});
  EXPECT_EQ(ok.wait(20), 0) << ok.output();
}
