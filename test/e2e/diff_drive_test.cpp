// diff_bot end to end in lockstep: a 1 m square driven by time over cmd_vel
// (the sim paused and stepped exactly, so each command lands on a known step),
// diff_drive_controller's odometry against sim_server's ground truth within
// 5 %, and the square driven again after a reset repeating the first bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"
#include "tools/lib/clients/sim_client.hpp"

namespace lcm_control::testing {
namespace {

constexpr int kChunk = 250;  // control steps per cmd_vel (0.25 s; cmd_vel_timeout is 0.5 s)

struct Square {
  std::vector<odometry_t> odom, truth;  // at every corner
  std::map<int64_t, std::vector<double>> odom_by_time;  // x, y, yaw
};

class DiffBotSession {
 public:
  DiffBotSession()
      : robot_(source("config/diff_bot.urdf"), source("config/diff_bot.yaml")),
        bus_(robot_.url(), ""),
        odom_(bus_.lcm(), "diff_drive_controller/odom"),
        truth_(bus_.lcm(), "sim_server/base_pose"),
        sim_client_(bus_, "diff_drive_test") {}

  void start() {
    robot_.start_controller_manager();
    robot_.start_sim({"--floating-base", "--mode", "lockstep", "--paused"});
    robot_.spawn({"joint_state_controller", "diff_drive_controller"});
  }

  // v m/s and w rad/s for `seconds` of sim time, a fresh cmd_vel every kChunk steps.
  void drive(double v, double w, double seconds) {
    twist_t t{};
    t.linear.x = v;
    t.angular.z = w;
    const int chunks = int(std::lround(seconds * 1000 / kChunk));
    for (int k = 0; k < chunks; ++k) {
      bus_.lcm().publish("diff_drive_controller/cmd_vel", &t);
      // The controller manager must have it before the first state of the steps: datagrams sent by different
      // processes (this one, then sim_server) are not ordered on loopback when they leave from different CPUs.
      pump_until(bus_.lcm(), [] { return false; }, 0.01);
      const sim_response_t r = sim_client_.step(kChunk, 10);
      ASSERT_TRUE(r.ok) << r.message;
    }
  }

  Square square() {
    Square s;
    odom_.messages.clear();
    truth_.messages.clear();
    for (int side = 0; side < 4; ++side) {
      drive(0.2, 0, 5.0);           // 1 m (less the 0.2 s to accelerate at 1 m/s^2)
      drive(0, M_PI / 2 / 2, 2.0);  // a quarter turn at 0.785 rad/s
      drive(0, 0, 0.5);             // stand still
      pump_until(bus_.lcm(), [] { return false; }, 0.2);
      s.odom.push_back(odom_.messages.back());
      s.truth.push_back(truth_.messages.back());
    }
    for (const auto& m : odom_.messages) s.odom_by_time[m.utime] = {m.position.x, m.position.y, m.yaw};
    return s;
  }

  tools::SimClient& sim() { return sim_client_; }
  void settle() { pump_until(bus_.lcm(), [] { return false; }, 0.1); }
  std::string cm_output() const { return robot_.cm_output(); }

 private:
  RobotSession robot_;
  Bus bus_;
  Recorder<odometry_t> odom_, truth_;
  tools::SimClient sim_client_;
};

TEST(DiffDrive, ASquareByTimeOdometryWithinFivePercentOfGroundTruthAndRepeatedBitForBitAfterAReset) {
  DiffBotSession s;
  ASSERT_NO_FATAL_FAILURE(s.start());
  // Seen a few times in 10 runs: a cmd_vel published at once after the spawner's ready did not reach the first
  // steps (not explained yet); the controllers have run for 0.1 s of wall time before the first one here.
  s.settle();
  const Square first = s.square();
  double travelled = 0;
  for (int c = 0; c < 4; ++c) {
    const odometry_t& o = first.odom[c];
    const odometry_t& g = first.truth[c];
    travelled += 1.0;
    const double error = std::hypot(o.position.x - g.position.x, o.position.y - g.position.y);
    const double yaw_error = std::abs(std::remainder(o.yaw - g.yaw, 2 * M_PI));
    std::printf("corner %d: odometry (%.4f, %.4f, %.4f rad), ground truth (%.4f, %.4f, %.4f rad): %.4f m off after "
                "%.0f m, heading %.4f rad off\n",
                c + 1, o.position.x, o.position.y, o.yaw, g.position.x, g.position.y, g.yaw, error, travelled,
                yaw_error);
    EXPECT_LT(error, 0.05 * travelled) << "corner " << c + 1;
    EXPECT_LT(yaw_error, 0.05 * (c + 1) * M_PI / 2) << "corner " << c + 1;
    EXPECT_NEAR(std::abs(std::remainder(g.yaw - (c + 1) * M_PI / 2, 2 * M_PI)), 0.0, 0.1) << "a quarter turn each";
  }
  const odometry_t& end = first.truth.back();
  EXPECT_LT(std::hypot(end.position.x, end.position.y), 0.15) << "back near the start";
  const odometry_t& c1 = first.truth.front();
  EXPECT_NEAR(c1.position.x, 0.98, 0.05);  // the first side: 1 m less the acceleration

  ASSERT_TRUE(s.sim().reset({}, 5).ok);
  s.settle();  // the controller manager restarts its controllers on the reset's state before the first cmd_vel
  const Square second = s.square();
  // The first run's controllers started on the paused step 0 and first updated at step 1; after the reset they
  // restart at step 0 and update in that cycle, so the first odometry message comes 1 ms earlier. From the second
  // message on, the publish times are the same.
  int64_t compared = 0;
  for (const auto& [t, v] : first.odom_by_time) {
    const auto it = second.odom_by_time.find(t);
    if (it == second.odom_by_time.end()) continue;
    ++compared;
    ASSERT_EQ(v, it->second) << "lockstep: the same commands, the same odometry; first difference at t=" << t
                             << " us: x " << v[0] << " vs " << it->second[0];
  }
  EXPECT_GE(compared, 1499);
  for (int c = 0; c < 4; ++c) {
    EXPECT_EQ(first.truth[c].position.x, second.truth[c].position.x);
    EXPECT_EQ(first.truth[c].position.y, second.truth[c].position.y);
  }
}

}  // namespace
}  // namespace lcm_control::testing
