// ROS 2 chaining end to end on our own robots, in lockstep: a JointTrajectoryController whose command_joints are the
// position references of a pid_controller that commands ur_like's joints in effort (test/robots/ur_like_chained.yaml):
// send-trajectory names the joints the chain ends at; the goal SUCCEEDS within the YAML's tolerances, and the same
// goal through the same JTC commanding effort with the same gains is compared. And a JTC writing the references of
// an admittance controller on ft_arm (test/robots/ft_arm.yaml): a 10 N push on the tool (cmctl apply-body-wrench)
// moves it F/k along the push, and it comes back when the push ends.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <regex>
#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"
#include "description/kinematics.hpp"
#include "tools/lib/clients/sim_client.hpp"
#include "description/load.hpp"

namespace lcm_control::testing {
namespace {

// "largest final error X ..., largest path error Y" of a SUCCEEDED result.
std::pair<double, double> errors_in(const std::string& out) {
  std::smatch m;
  if (!std::regex_search(out, m, std::regex(R"(largest final error ([0-9.]+).*largest path error ([0-9.]+))")))
    return {NAN, NAN};
  return {std::stod(m[1]), std::stod(m[2])};
}

TEST(Chaining, AJointTrajectoryControllerOnPidReferencesReachesItsGoalOnAnEffortArm) {
  LockstepSession robot(source("test/robots/ur_like.urdf"), source("test/robots/ur_like_chained.yaml"), {});
  ASSERT_NO_FATAL_FAILURE(robot.start({"joint_state_broadcaster", "arm_pids", "arm_trajectory"}));
  const std::string goal = "2:0.3,-0.5,0.6,0.3,0.3,0.3";
  std::string out;
  ASSERT_EQ(robot.send({"arm_trajectory", "--point", goal}, out), 0) << out << robot.cm_output();
  EXPECT_NE(out.find("arm_trajectory: SUCCEEDED"), std::string::npos) << out;
  const auto chained = errors_in(out);

  std::string switched;
  ASSERT_EQ(robot.run({"cmctl", "load", "arm_effort_trajectory"}, &switched), 0) << switched;
  ASSERT_EQ(robot.run({"cmctl", "switch", "--start", "arm_effort_trajectory", "--stop", "arm_trajectory", "--stop",
                       "arm_pids"},
                      &switched),
            0)
      << switched;
  ASSERT_EQ(robot.send({"arm_effort_trajectory", "--point", "2:0,0,0,0,0,0"}, out), 0) << out;
  ASSERT_EQ(robot.send({"arm_effort_trajectory", "--point", goal}, out), 0) << out;
  EXPECT_NE(out.find("arm_effort_trajectory: SUCCEEDED"), std::string::npos) << out;
  const auto direct = errors_in(out);
  std::printf("JTC -> PID (effort): final error %.6f, path error %.6f rad; JTC on effort, same gains: final %.6f, "
              "path %.6f rad\n",
              chained.first, chained.second, direct.first, direct.second);
  EXPECT_LT(chained.first, 0.02) << "within the goal tolerance";
  EXPECT_LT(chained.second, 0.1) << "within the path tolerance";
}

// The tool's position in the world from the newest joint_states.
Eigen::Vector3d tool_position(const RobotModel& model, const joint_state_t& s) {
  std::map<std::string, double> q;
  for (int k = 0; k < s.num_joints; ++k) q[s.name[size_t(k)]] = s.position[size_t(k)];
  for (const LinkPose& l : forward_kinematics(model, q))
    if (l.link == "tool") return l.pose.translation();
  return Eigen::Vector3d::Constant(NAN);
}

// One run of the push: the joint positions of every joint_states message, the tool's start and its position during
// and after the push.
struct PushRun {
  std::map<int64_t, std::vector<double>> positions;  // by the message's sim time
  Eigen::Vector3d p0, p1, p2;
  std::string output;
};

void push_run(PushRun& run) {
  RobotSession robot(source("test/robots/ft_arm.urdf"), source("test/robots/ft_arm.yaml"));
  const RobotModel model = load_robot_model(source("test/robots/ft_arm.urdf"), source("test/robots/ft_arm.yaml"));
  Bus bus(robot.url(), "");
  Recorder<joint_state_t> states(bus.lcm(), "joint_states");
  tools::SimClient sim(bus, "chaining_test");
  robot.start_controller_manager();
  ASSERT_NO_FATAL_FAILURE(robot.start_sim({"--mode", "lockstep", "--paused"}));
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_broadcaster", "admittance_controller", "arm_trajectory"}));
  auto step = [&](int64_t n) {
    const sim_response_t r = sim.step(n, 60);
    ASSERT_TRUE(r.ok) << r.message;
    pump_until(bus.lcm(), [] { return false; }, 0.05);
  };
  ASSERT_NO_FATAL_FAILURE(step(200));
  ASSERT_FALSE(states.messages.empty());
  run.p0 = tool_position(model, states.messages.back());
  const sim_response_t pushed = sim.apply_wrench("tool", {10, 0, 0}, {0, 0, 0}, 3.0, 10);
  ASSERT_TRUE(pushed.ok) << pushed.message;
  ASSERT_NO_FATAL_FAILURE(step(2500));
  run.p1 = tool_position(model, states.messages.back());
  ASSERT_NO_FATAL_FAILURE(step(2000));  // the push ended at 3 s
  run.p2 = tool_position(model, states.messages.back());
  for (const joint_state_t& m : states.messages) run.positions[m.utime] = m.position;
  run.output = robot.cm_output();
}

// Twice: the second run's joint_states equal the first's bit for bit (lockstep, with a chain and a push).
TEST(Chaining, AnAdmittanceControllerUnderATrajectoryControllerYieldsToAPushAsItsSpring) {
  PushRun first, second;
  ASSERT_NO_FATAL_FAILURE(push_run(first));
  ASSERT_NO_FATAL_FAILURE(push_run(second));
  const double force = 10, stiffness = 200;
  const Eigen::Vector3d d = first.p1 - first.p0, back = first.p2 - first.p0;
  std::printf("10 N along x: the tool moved (%.5f, %.5f, %.5f) m (F/k = %.3f m); 1.5 s after the push (%.5f, %.5f, "
              "%.5f) m from where it started\n",
              d.x(), d.y(), d.z(), force / stiffness, back.x(), back.y(), back.z());
  EXPECT_NEAR(d.x(), force / stiffness, 0.1 * force / stiffness) << first.output;
  EXPECT_LT(std::hypot(d.y(), d.z()), 0.005) << "along the push";
  EXPECT_LT(back.norm(), 0.002) << "back where it was";
  // The messages of the same sim time (both recorders may have missed one at the ends).
  size_t n = 0, differing = 0;
  std::string first_difference;
  for (const auto& [utime, q] : first.positions) {
    const auto other = second.positions.find(utime);
    if (other == second.positions.end()) continue;
    ++n;
    differing += other->second != q;
    for (size_t j = 0; j < q.size() && first_difference.empty() && j < other->second.size(); ++j)
      if (q[j] != other->second[j])
        first_difference = fmt::format("first at t={} us, joint {}: {:.17g} then {:.17g}", utime, j, q[j],
                                       other->second[j]);
  }
  EXPECT_EQ(first.positions.begin()->first, second.positions.begin()->first) << "the first joint_states' time";
  ASSERT_GT(n, 4000u);
  std::printf("two runs: %zu joint_states messages compared, %zu differ\n", n, differing);
  EXPECT_EQ(differing, 0u) << "lockstep repeats a chained run bit for bit; " << first_difference;
}

}  // namespace
}  // namespace lcm_control::testing
