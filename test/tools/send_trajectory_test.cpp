// send-trajectory against the real sim_server and controller_manager (turret_bot
// with a JointTrajectoryController, in lockstep): goals from --point, YAML and
// CSV reach their positions; a rejected goal, a goal tolerance that cannot be
// met, a missing controller and a stalled one each exit non-zero with the reason.
#include <gtest/gtest.h>
#include <signal.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <tuple>

#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

struct Outcome {
  int rc = -1;
  std::string out, err;
};

// Runs send-trajectory to completion with stdout and stderr apart.
Outcome send_trajectory(std::vector<std::string> args, const std::string& url, double timeout_s = 20.0) {
  const std::string dir = temp_dir("send_trajectory");
  std::vector<std::string> argv{"/bin/sh", "-c", "exec \"$0\" \"$@\" 2>\"" + dir + "/stderr\"", bin("send-trajectory")};
  argv.insert(argv.end(), args.begin(), args.end());
  argv.insert(argv.end(), {"--lcm-url", url});
  ChildProcess p(argv);
  Outcome r;
  r.rc = p.wait(timeout_s);
  r.out = p.output();
  r.err = read_text(dir + "/stderr");
  return r;
}

std::string shown(const Outcome& r) { return "exit " + std::to_string(r.rc) + "\nstdout:\n" + r.out + "stderr:\n" + r.err; }

// j1 and j2 from joint_states 2 s of sim time from now, once the robot has
// settled at the last point it holds.
std::pair<double, double> positions_now(const std::string& url) {
  lcm::LCM lc(url);
  Recorder<joint_state_t> js(lc, "joint_states");
  EXPECT_TRUE(pump_until(
      lc, [&] { return js.messages.size() > 1 && js.messages.back().utime - js.messages.front().utime >= 2000000; },
      10.0));
  if (js.messages.empty()) return {NAN, NAN};
  const joint_state_t& m = js.messages.back();
  double j1 = NAN, j2 = NAN;
  for (int k = 0; k < m.num_joints; ++k) (m.name[k] == "j1" ? j1 : j2) = m.position[k];
  return {j1, j2};
}

class SendTrajectory : public ::testing::Test {
 protected:
  void launch(const std::string& file) {
    robot_ = std::make_unique<ChildProcess>(
        std::vector<std::string>{bin("launch"), file, "--mode", "lockstep", "--lcm-url", url_});
    ASSERT_TRUE(robot_->wait_for_output("[launch] up:", 25.0)) << robot_->output();
  }
  void TearDown() override {
    if (robot_) {
      EXPECT_EQ(robot_->stop(8.0), 0) << robot_->output();
    }
  }
  std::string url_ = unique_lcm_url();
  std::unique_ptr<ChildProcess> robot_;
};

}  // namespace

TEST_F(SendTrajectory, MovesTheJointsAndExitsZeroFromPointsYamlAndCsv) {
  launch(source("config/turret_bot_trajectory.launch.yaml"));
  // --point, joints from the controller manager: 0.3 (m, rad) in 2 s.
  Outcome r = send_trajectory({"trajectory_controller", "--point", "2:0.3,0.3"}, url_);
  ASSERT_EQ(r.rc, 0) << shown(r);
  EXPECT_TRUE(r.out.rfind("trajectory_controller: SUCCEEDED: goal ", 0) == 0) << shown(r);
  EXPECT_TRUE(has(r.out, " reached: largest final error ")) << shown(r);
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << shown(r);
  EXPECT_EQ(r.err, "");
  std::printf("send-trajectory: %s", r.out.c_str());
  auto [j1, j2] = positions_now(url_);
  EXPECT_NEAR(j1, 0.3, 0.01);  // the goal tolerance
  EXPECT_NEAR(j2, 0.3, 0.01);

  // ROS's topic name, a YAML goal with ROS durations, back to 0.1, 0.
  const std::string dir = temp_dir("send_trajectory_files");
  std::ofstream(dir + "/goal.yaml") << "joint_names: [j2, j1]\npoints:\n"
                                    << "  - positions: [0.6, 0.2]\n    time_from_start: {secs: 1, nsecs: 0}\n"
                                    << "  - positions: [0.0, 0.1]\n    velocities: [0, 0]\n"
                                    << "    time_from_start: {secs: 2, nsecs: 500000000}\n";
  r = send_trajectory({"/trajectory_controller/command", "--file", dir + "/goal.yaml"}, url_);
  ASSERT_EQ(r.rc, 0) << shown(r);
  std::tie(j1, j2) = positions_now(url_);
  EXPECT_NEAR(j1, 0.1, 0.01);
  EXPECT_NEAR(j2, 0.0, 0.01);

  // CSV, then --relative: offsets from where the joints are.
  std::ofstream(dir + "/goal.csv") << "time,j1,j2\n1,0.2,-0.2\n2,0.4,-0.4\n";
  r = send_trajectory({"trajectory_controller", "--csv", dir + "/goal.csv"}, url_);
  ASSERT_EQ(r.rc, 0) << shown(r);
  std::tie(j1, j2) = positions_now(url_);
  EXPECT_NEAR(j1, 0.4, 0.01);
  EXPECT_NEAR(j2, -0.4, 0.01);
  r = send_trajectory({"trajectory_controller", "--relative", "--point", "1.5:-0.1,0.5", "--verbose"}, url_);
  ASSERT_EQ(r.rc, 0) << shown(r);
  double start1 = NAN, start2 = NAN;
  ASSERT_EQ(std::sscanf(r.out.c_str(), "start (joint_states): j1 %lf, j2 %lf", &start1, &start2), 2) << shown(r);
  EXPECT_NEAR(start1, 0.4, 0.01);
  EXPECT_NEAR(start2, -0.4, 0.01);
  EXPECT_TRUE(has(r.out, "sent goal ")) << shown(r);
  EXPECT_TRUE(has(r.out, " on 'trajectory_controller/command': 1 point over 1.5 s for j1, j2; waiting up to 11.5 s"))
      << shown(r);
  EXPECT_TRUE(has(r.out, "\nfeedback 0.00 s: j1 desired ")) << shown(r);
  const auto feedback_lines = split(r.out, '\n');
  EXPECT_GE(std::count_if(feedback_lines.begin(), feedback_lines.end(),
                          [](const std::string& l) { return l.rfind("feedback ", 0) == 0; }),
            6)  // 4 a second over 1.5 s
      << shown(r);
  EXPECT_TRUE(has(r.out, "\ntrajectory_controller: SUCCEEDED: goal ")) << shown(r);
  std::tie(j1, j2) = positions_now(url_);
  EXPECT_NEAR(j1, start1 - 0.1, 0.01);
  EXPECT_NEAR(j2, start2 + 0.5, 0.01);

  // --no-wait only sends; CONTROLLER may come after the options.
  r = send_trajectory({"--no-wait", "--point", "1:0,0", "trajectory_controller"}, url_);
  ASSERT_EQ(r.rc, 0) << shown(r);
  EXPECT_TRUE(has(r.out, " on 'trajectory_controller/command': 1 point over 1 s for j1, j2\n")) << shown(r);
}

TEST_F(SendTrajectory, RefusalsExitNonZeroNamingTheStatusTheJointOrTheController) {
  launch(source("config/turret_bot_trajectory.launch.yaml"));
  // A joint the controller does not have: its REJECTED result.
  Outcome r = send_trajectory({"trajectory_controller", "--joints", "j1,j3", "--point", "1:0.1,0.1"}, url_);
  EXPECT_EQ(r.rc, 1) << shown(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(has(r.err, "send-trajectory: error: trajectory_controller: REJECTED: goal ")) << shown(r);
  EXPECT_TRUE(has(r.err, " rejected: joint 'j3' is not controlled here (joints: j1, j2)\n")) << shown(r);

  // Bad waypoints never reach the bus: exit 3, the --point named.
  r = send_trajectory({"trajectory_controller", "--point", "1:0.1,0.1", "--point", "0.5:0,0"}, url_);
  EXPECT_EQ(r.rc, 3) << shown(r);
  EXPECT_EQ(r.err, "send-trajectory: error: --point 2 ('0.5:0,0'): time 0.5 must be after the previous point's 1 "
                   "(times count from the start and increase)\n");
  r = send_trajectory({"trajectory_controller", "--point", "1:0.1"}, url_);
  EXPECT_EQ(r.rc, 3) << shown(r);
  EXPECT_EQ(r.err, "send-trajectory: error: --point 1 ('1:0.1'): 1 position for 2 joints (j1, j2; from the joints of "
                   "'trajectory_controller'); give one value per joint\n");
  r = send_trajectory({"trajectory_controller", "--file", "/nonexistent/goal.yaml"}, url_);
  EXPECT_EQ(r.rc, 3) << shown(r);
  EXPECT_TRUE(has(r.err, "/nonexistent/goal.yaml: trajectory YAML file not found (check the path passed with --file)"))
      << shown(r);

  // A misspelled controller, and one that is not a trajectory controller.
  r = send_trajectory({"trajectory_controler", "--point", "1:0,0"}, url_);
  EXPECT_EQ(r.rc, 1) << shown(r);
  EXPECT_TRUE(has(r.err, "no controller 'trajectory_controler' in the controller manager (loaded: "
                         "joint_state_controller, trajectory_controller): load and start it with `spawner "
                         "trajectory_controler` (a controller of the ros_control YAML); did you mean "
                         "'trajectory_controller'?"))
      << shown(r);
  r = send_trajectory({"joint_state_controller", "--point", "1:0,0"}, url_);
  EXPECT_EQ(r.rc, 1) << shown(r);
  EXPECT_TRUE(has(r.err, "send-trajectory: error: joint_state_controller (joint_state_controller/JointStateController) "
                         "takes no commands (it only reads the joints and publishes joint_states); joint_trajectory_t "
                         "was given on joint_state_controller/command: command a controller that drives the joints "
                         "instead (cmctl list)\n"))
      << shown(r);

  // No controller, no waypoints, or two sources: usage.
  r = send_trajectory({"--point", "1:0,0"}, url_);
  EXPECT_EQ(r.rc, 2) << shown(r);
  EXPECT_TRUE(has(r.err, "CONTROLLER is required")) << shown(r);
  r = send_trajectory({"trajectory_controller"}, url_);
  EXPECT_EQ(r.rc, 2) << shown(r);
  EXPECT_TRUE(has(r.err, "give the waypoints with one of: --point TIME:POSITIONS (repeatable), --file goal.yaml or "
                         "--csv goal.csv"))
      << shown(r);
}

// Every publishing tool asks the controller manager what the controller's command channel takes and refuses another
// type with exit 1, naming both and the tool to use (issue 32, item 1); a goal that fails under the e-stop says so.
TEST_F(SendTrajectory, PublishingToolsRefuseTheWrongTypeAndAFailureUnderTheEStopNamesIt) {
  launch(source("config/turret_bot_trajectory.launch.yaml"));
  const std::string takes = "trajectory_controller takes joint_trajectory_t on trajectory_controller/command; ";
  auto run_tool = [&](std::vector<std::string> argv) {
    argv.insert(argv.end(), {"--lcm-url", url_});
    ChildProcess p(argv);
    const int rc = p.wait(10.0);
    return std::make_pair(rc, p.output());
  };
  auto [rc, out] = run_tool({bin("turret-cmd"), "trajectory_controller", "0.5"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_EQ(out, "turret-cmd: error: " + takes + "float64_t was given: use send-trajectory trajectory_controller ...\n");
  std::tie(rc, out) = run_tool({bin("bus"), "pub", "/trajectory_controller/command", "float64_t", "data=0.5"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_EQ(out, "bus: error: " + takes + "float64_t was given: use send-trajectory trajectory_controller ...\n");
  std::tie(rc, out) = run_tool({bin("drive"), "trajectory_controller", "0.1", "0", "--duration", "0.2"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_EQ(out, "drive: error: " + takes +
                     "twist_t was given on trajectory_controller/cmd_vel: use send-trajectory trajectory_controller ...\n");
  std::tie(rc, out) = run_tool({bin("gripper"), "trajectory_controller", "--position", "0.01"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_EQ(out, "gripper: error: " + takes +
                     "gripper_command_t was given: use send-trajectory trajectory_controller ...\n");
  // A channel no controller commands is published as before, with a warning that nothing listens there.
  std::tie(rc, out) = run_tool({bin("bus"), "pub", "other/command", "float64_t", "data=0.5"});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_TRUE(has(out, "bus: warning: no loaded controller takes commands on 'other/command': nothing listens there "
                       "(the controllers' command channels: "))
      << out;
  EXPECT_TRUE(has(out, "trajectory_controller/command")) << out;
  // ROS 2's name of the JTC's topic is its command channel here: said, then checked as that channel.
  std::tie(rc, out) = run_tool({bin("bus"), "pub", "/trajectory_controller/joint_trajectory", "float64_t", "data=0.5"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_EQ(out, "bus: 'trajectory_controller/joint_trajectory' is ROS 2's name; here the channel is "
                 "'trajectory_controller/command'\nbus: error: " +
                     takes + "float64_t was given: use send-trajectory trajectory_controller ...\n");

  std::tie(rc, out) = run_tool({bin("bus"), "pub", "e_stop", "e_stop_t", "engaged=true", "source=test"});
  ASSERT_EQ(rc, 0) << out;
  const Outcome r = send_trajectory({"trajectory_controller", "--point", "1:0.5,0.5"}, url_);
  EXPECT_EQ(r.rc, 1) << shown(r);
  EXPECT_TRUE(has(r.err, "send-trajectory: error: trajectory_controller: PATH_TOLERANCE_VIOLATED because the e-stop is "
                         "engaged: the hardware holds still (release it: bus pub e_stop e_stop_t engaged=false, or the "
                         "dashboard's e-stop button); the controller says: "))
      << shown(r);

  // Paused: the goal gets no result, and the reason is the simulator, not the controller.
  std::tie(rc, out) = run_tool({bin("bus"), "pub", "e_stop", "e_stop_t", "engaged=false", "source=test"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run_tool({bin("cmctl"), "pause"});
  ASSERT_EQ(rc, 0) << out;
  const Outcome paused = send_trajectory({"trajectory_controller", "--point", "1:0,0", "--result-timeout", "2"}, url_);
  EXPECT_EQ(paused.rc, 4) << shown(paused);
  EXPECT_TRUE(has(paused.err, "it is running but sent no feedback for this goal on 'trajectory_controller/feedback': "
                              "the simulator is paused: its time does not advance (cmctl resume)\n"))
      << shown(paused);
}

TEST_F(SendTrajectory, GoalToleranceViolatedNamesTheJoint) {
  launch(source("test/tools/data/turret_bot_tight_trajectory.launch.yaml"));
  const Outcome r = send_trajectory({"tight_trajectory_controller", "--point", "1:0,0.3"}, url_);
  EXPECT_EQ(r.rc, 1) << shown(r);
  EXPECT_EQ(r.out, "");
  EXPECT_TRUE(has(r.err, "send-trajectory: error: tight_trajectory_controller: GOAL_TOLERANCE_VIOLATED: goal tolerance "
                         "violated on joint 'j2': error "))
      << shown(r);
  EXPECT_TRUE(has(r.err, "(tolerance 0.000001)")) << shown(r);
  std::printf("%s", r.err.c_str());
}

TEST_F(SendTrajectory, CtrlCStopsTheControllerWithAnEmptyTrajectory) {
  launch(source("config/turret_bot_trajectory.launch.yaml"));
  ChildProcess p({bin("send-trajectory"), "trajectory_controller", "--point", "600:0.5,0.5", "--verbose", "--lcm-url",
                  url_});
  ASSERT_TRUE(p.wait_for_output("feedback 0.00 s", 10.0)) << p.output();
  EXPECT_EQ(p.stop(5.0, SIGINT), 130) << p.output();
  EXPECT_TRUE(has(p.output(), "send-trajectory: interrupted: sent an empty trajectory to stop 'trajectory_controller' "
                              "(goal "))
      << p.output();
  EXPECT_TRUE(has(p.output(), ": PREEMPTED: stopped by an empty trajectory (goal ")) << p.output();
  // Stopped on the way: nowhere near 0.5 after 600 s.
  const auto [j1, j2] = positions_now(url_);
  EXPECT_LT(j1, 0.25);
  EXPECT_LT(j2, 0.25);
}

// Without sim_server the controller manager runs the controller but its time
// stands still: no result, no feedback, and no joint_states for --relative.
TEST(SendTrajectoryNoSim, TimeoutsSayWhatIsMissing) {
  const std::string url = unique_lcm_url();
  Outcome r = send_trajectory({"trajectory_controller", "--point", "1:0,0", "--timeout", "0.5"}, url);
  EXPECT_EQ(r.rc, 4) << shown(r);
  EXPECT_TRUE(has(r.err, "no answer from the controller manager within 0.5 s to list")) << shown(r);

  ChildProcess cm({bin("controller_manager"), "--urdf", source("config/turret_bot.urdf"), "--config",
                   source("config/turret_bot_trajectory.yaml"), "--lcm-url", url});
  ASSERT_TRUE(cm.wait_for_output("ready (", 10.0)) << cm.output();
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "trajectory_controller", "--lcm-url", url});
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();

  r = send_trajectory({"trajectory_controller", "--point", "0.5:0,0", "--result-timeout", "1"}, url);
  EXPECT_EQ(r.rc, 4) << shown(r);
  EXPECT_EQ(r.err, "send-trajectory: error: no result from 'trajectory_controller' on 'trajectory_controller/result' "
                   "within 1 s: it is running but sent no feedback for this goal on 'trajectory_controller/feedback': "
                   "does its time advance? (is sim_server running and stepping?)\n");

  r = send_trajectory({"trajectory_controller", "--relative", "--point", "0.5:0,0", "--timeout", "0.5"}, url);
  EXPECT_EQ(r.rc, 4) << shown(r);
  EXPECT_EQ(r.err, "send-trajectory: error: --relative needs the current positions, but no valid joint_state_t came "
                   "on 'joint_states' within 0.5 s (no other channel either); the controller manager runs "
                   "'joint_state_controller', so its time does not advance: is sim_server running and stepping?\n");
  EXPECT_EQ(spawner.stop(5.0), 0) << spawner.output();
}
