// A mobile robot in lockstep for end-to-end tests: controller_manager, sim_server paused, the controllers spawned;
// twists sent a chunk of control steps at a time and the steps taken exactly, so that every run is the same. The
// drive's odometry, the free base's ground truth (sim_server/base_pose) and joint_states are recorded.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"
#include "tools/lib/clients/sim_client.hpp"

namespace lcm_control::testing {

// A pose in the plane.
struct Pose2 {
  double x = 0, y = 0, yaw = 0;
};

inline Pose2 pose_of(const odometry_t& m) { return {m.position.x, m.position.y, m.yaw}; }

// `p` seen from `origin`'s frame.
inline Pose2 relative(const Pose2& origin, const Pose2& p) {
  const double c = std::cos(origin.yaw), s = std::sin(origin.yaw), dx = p.x - origin.x, dy = p.y - origin.y;
  return {c * dx + s * dy, -s * dx + c * dy, std::remainder(p.yaw - origin.yaw, 2 * M_PI)};
}

inline double angle_between(double a, double b) { return std::abs(std::remainder(a - b, 2 * M_PI)); }

class MobileSession {
 public:
  // command_channel takes twist_t; odometry_channel publishes odometry_t; `flags` go to both servers (e.g.
  // --xacro-arg, --package-path); rate_hz is the control rate the config sets.
  MobileSession(std::string urdf, std::string config, std::vector<std::string> controllers,
                std::string command_channel, const std::string& odometry_channel, std::vector<std::string> flags = {},
                double rate_hz = 100)
      : robot_(std::move(urdf), std::move(config)),
        bus_(robot_.url(), ""),
        controllers_(std::move(controllers)),
        command_(std::move(command_channel)),
        odom_(bus_.lcm(), odometry_channel),
        truth_(bus_.lcm(), "sim_server/base_pose"),
        states_(bus_.lcm(), "joint_states"),
        sim_client_(bus_, "mobile_session"),
        flags_(std::move(flags)),
        rate_hz_(rate_hz),
        chunk_(std::max(1, int(std::lround(0.05 * rate_hz)))) {}

  void start(const std::vector<std::string>& sim_flags = {}) {
    robot_.start_controller_manager(flags_);
    std::vector<std::string> sim = flags_;
    sim.insert(sim.end(), {"--mode", "lockstep", "--paused"});
    sim.insert(sim.end(), sim_flags.begin(), sim_flags.end());
    robot_.start_sim(sim);
    robot_.spawn(controllers_);
    pump_until(bus_.lcm(), [] { return false; }, 0.1);
  }

  // `steps` control steps with no command (the drive's timeout passes: it stops).
  void idle(int steps) {
    const sim_response_t r = sim_client_.step(steps, 30);
    ASSERT_TRUE(r.ok) << r.message;
    settle();
  }

  // vx, vy m/s and wz rad/s, a fresh twist every chunk of steps (0.05 s), until `done` or max_s of sim time; then,
  // with `stop`, a zero twist (as the drive tool ends), so that the drive does not go on until its timeout.
  void drive(double vx, double vy, double wz, double max_s, const std::function<bool()>& done = {},
             bool stop = true) {
    twist_t t{};
    t.linear.x = vx;
    t.linear.y = vy;
    t.angular.z = wz;
    const int chunks = int(std::lround(max_s / twist_period()));
    for (int k = 0; k <= chunks; ++k) {
      if (k == chunks || (done && done())) {
        if (!stop) return;
        t = twist_t{};
      }
      bus_.lcm().publish(command_, &t);
      // The controller manager must have it before the steps' first state (datagrams from two processes are not
      // ordered on loopback).
      pump_until(bus_.lcm(), [] { return false; }, 0.005);
      const sim_response_t r = sim_client_.step(chunk_, 10);
      ASSERT_TRUE(r.ok) << r.message;
      settle();
      if (t.linear.x == 0 && t.linear.y == 0 && t.angular.z == 0) return;
    }
  }

  double twist_period() const { return chunk_ / rate_hz_; }
  void settle() { pump_until(bus_.lcm(), [] { return false; }, 0.02); }
  Pose2 odometry() const { return odom_.messages.empty() ? Pose2{} : pose_of(odom_.messages.back()); }
  Pose2 truth() const { return truth_.messages.empty() ? Pose2{} : pose_of(truth_.messages.back()); }
  const odometry_t& truth_message() const { return truth_.messages.back(); }
  const std::vector<odometry_t>& odometry_messages() const { return odom_.messages; }
  const std::vector<odometry_t>& truth_messages() const { return truth_.messages; }
  const joint_state_t& joint_states() const { return states_.messages.back(); }
  double position(const std::string& joint) const { return field(joint, &joint_state_t::position); }
  double velocity(const std::string& joint) const { return field(joint, &joint_state_t::velocity); }
  Bus& bus() { return bus_; }
  RobotSession& robot() { return robot_; }
  std::string output() const { return robot_.cm_output() + robot_.sim_output(); }

 private:
  double field(const std::string& joint, std::vector<double> joint_state_t::*values) const {
    if (states_.messages.empty()) {
      ADD_FAILURE() << "no joint_states yet";
      return NAN;
    }
    const joint_state_t& s = states_.messages.back();
    for (int i = 0; i < s.num_joints; ++i)
      if (s.name[size_t(i)] == joint) return (s.*values)[size_t(i)];
    ADD_FAILURE() << "no joint '" << joint << "' in joint_states";
    return NAN;
  }

  RobotSession robot_;
  Bus bus_;
  std::vector<std::string> controllers_;
  std::string command_;
  Recorder<odometry_t> odom_, truth_;
  Recorder<joint_state_t> states_;
  tools::SimClient sim_client_;
  std::vector<std::string> flags_;
  double rate_hz_;
  int chunk_;
};

}  // namespace lcm_control::testing
