// ROS 2 chaining end to end on our own robot, in lockstep: a JointTrajectoryController whose command_joints are the
// position references of a pid_controller that commands ur_like's joints in effort (test/robots/ur_like_chained.yaml).
// send-trajectory names the joints the chain ends at; the goal SUCCEEDS within the YAML's tolerances, and the same
// goal through the same JTC commanding effort with the same gains is compared.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <regex>
#include <string>

#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

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

}  // namespace
}  // namespace lcm_control::testing
