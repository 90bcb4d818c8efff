// Robots as people bring them from ROS, end to end with the real programs, on
// the project's own test robots (test/robots): a namespaced YAML under launch,
// an arm whose default start is outside its limits, trajectories sent with
// send-trajectory, a light upright arm under stiff gains (test/e2e/data). With ../shared/robots present, the real
// UR5 as well.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>

#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/odometry_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

std::string robot(const std::string& file) { return lt::source("test/robots/" + file); }

double position_of(const joint_state_t& s, const std::string& joint) {
  for (int k = 0; k < s.num_joints; ++k)
    if (s.name[k] == joint) return s.position[k];
  return NAN;
}

double velocity_of(const joint_state_t& s, const std::string& joint) {
  for (int k = 0; k < s.num_joints; ++k)
    if (s.name[k] == joint) return s.velocity[k];
  return NAN;
}

using Session = lt::LockstepSession;

// The real robots (../shared/robots, or $LCM_CONTROL_REAL_ROBOTS): run from their own files when present.
std::filesystem::path real_robots() {
  const char* env = std::getenv("LCM_CONTROL_REAL_ROBOTS");
  return env ? env : lt::source("../shared/robots");
}

// A real robot under `launch` from a launch file written with `yaml` (urdf:, config:, controllers: ...), until its
// controllers run; then `check(url)`.
void launch_real_robot(const std::string& name, const std::string& yaml, const std::string& started,
                       const std::string& package_path, const std::function<void(const std::string&)>& check) {
  const std::string file = lt::temp_dir("real_" + name) + "/" + name + ".launch.yaml";
  std::ofstream(file) << yaml;
  const std::string url = lt::unique_lcm_url();
  lt::ChildProcess launch({lt::bin("launch"), file, "--package-path", package_path, "--lcm-url", url,
                           "--stop-timeout", "20"});
  ASSERT_TRUE(launch.wait_for_output(started, 60)) << launch.output();
  check(url);
  EXPECT_EQ(launch.stop(30), 0) << launch.output();
}

// Joint positions from the newest joint_states on the session's bus.
joint_state_t latest_state(const Session& s, double timeout_s = 10) {
  lcm::LCM lc(s.url());
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  lt::pump_until(lc, [&] { return !states.messages.empty(); }, timeout_s);
  return states.messages.empty() ? joint_state_t{} : states.messages.back();
}

// The largest |velocity| of any joint over `seconds` of sim time of joint_states.
double worst_speed(const Session& s, double seconds) {
  lcm::LCM lc(s.url());
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  lt::pump_until(lc, [&] { return !states.messages.empty(); }, 10);
  if (states.messages.empty()) return INFINITY;
  const int64_t start = states.messages.front().utime;
  lt::pump_until(lc, [&] { return states.messages.back().utime - start >= int64_t(seconds * 1e6); }, 30);
  if (states.messages.back().utime - start < int64_t(seconds * 1e6)) return INFINITY;
  double worst = 0;
  for (const joint_state_t& m : states.messages)
    for (double v : m.velocity) worst = std::max(worst, std::abs(v));
  return worst;
}

const std::vector<std::string> kUrJoints{"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                         "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};

// Every joint 0.3 rad in 2 s with the UR's effort JointTrajectoryController; SUCCEEDED within its goal
// constraints (0.1 rad).
void ur_trajectory(Session& s) {
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_controller", "eff_joint_traj_controller"}));
  std::string out;
  const int rc = s.send({"eff_joint_traj_controller", "--point", "2:0.3,0.3,0.3,0.3,0.3,0.3"}, out);
  ASSERT_EQ(rc, 0) << out << s.sim_output();
  EXPECT_NE(out.find("eff_joint_traj_controller: SUCCEEDED"), std::string::npos) << out;
  const joint_state_t end = latest_state(s);
  for (const auto& j : kUrJoints) EXPECT_NEAR(position_of(end, j), 0.3, 0.1) << j;
}

}  // namespace

TEST(RealRobots, UrLikeArmFollowsAnEffortTrajectoryWithItsTwoPiLimits) {
  Session s(robot("ur_like.urdf"), robot("ur_like.yaml"), {});
  ur_trajectory(s);
}

TEST(RealRobots, FrankaLikeArmStartsInsideItsLimitsAndFollowsAPositionTrajectory) {
  Session s(robot("multi_trans_arm.urdf"), robot("multi_trans_arm.yaml"), {"--arg", "arm_id=arm"});
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_controller", "position_joint_trajectory_controller"}));
  EXPECT_NE(s.sim_output().find("joint 'arm_joint2' would start at 0 (no initial position given), outside its "
                                "limits [-3.07, -0.07]"),
            std::string::npos)
      << s.sim_output();
  const joint_state_t start = latest_state(s);
  EXPECT_NEAR(position_of(start, "arm_joint2"), -0.07, 1e-3);
  std::string out;
  ASSERT_EQ(s.send({"position_joint_trajectory_controller", "--point", "2:0.3,-0.5,0.3"}, out), 0) << out;
  const joint_state_t end = latest_state(s);
  EXPECT_NEAR(position_of(end, "arm_joint1"), 0.3, 0.01);
  EXPECT_NEAR(position_of(end, "arm_joint2"), -0.5, 0.05);
  EXPECT_NEAR(position_of(end, "arm_joint3"), 0.3, 0.05);
}

TEST(RealRobots, AnEffortArmStartsWhereToldAndDoesNotSagBeforeItsControllers) {
  Session s(robot("ur_like.urdf"), robot("ur_like.yaml"), {});
  // Only joint_state_controller: nothing commands the effort joints, the brakes hold them against gravity.
  ASSERT_NO_FATAL_FAILURE(
      s.start({"joint_state_controller"}, {"-J", "shoulder_lift_joint=-0.5", "--initial-position", "elbow_joint=1"}));
  const joint_state_t a = latest_state(s);
  const joint_state_t b = [&] {
    lcm::LCM lc(s.url());
    lt::Recorder<joint_state_t> states(lc, "joint_states");
    lt::pump_until(lc, [&] { return !states.messages.empty() && states.messages.back().utime > a.utime + 2'000'000; },
                   20);
    return states.messages.empty() ? joint_state_t{} : states.messages.back();
  }();
  ASSERT_GT(b.utime, a.utime + 2'000'000) << "less than 2 s of sim time";
  EXPECT_NEAR(position_of(b, "shoulder_lift_joint"), -0.5, 1e-3);
  EXPECT_NEAR(position_of(b, "elbow_joint"), 1.0, 1e-3);
  EXPECT_NEAR(position_of(b, "shoulder_pan_joint"), 0.0, 1e-3);
}

// The real Universal Robots UR5 from ../shared/robots (its URDF and YAML unchanged), when the checkout has them.
TEST(RealRobots, RealUr5FollowsATrajectoryWhenItsFilesArePresent) {
  const std::filesystem::path dir = real_robots();
  if (!std::filesystem::exists(dir / "ur5/urdf/ur5.urdf"))
    GTEST_SKIP() << "no " << (dir / "ur5").string() << " (set LCM_CONTROL_REAL_ROBOTS to the robots folder)";
  Session s((dir / "ur5/urdf/ur5.urdf").string(), (dir / "ur5/config/ur5_controllers.yaml").string(),
            {"--package-path", (dir / "ur5/pkgs").string()});
  ur_trajectory(s);
}

namespace {
// The real KUKA iiwa 14 (Drake's URDF with iiwa_stack's transmissions, namespace /iiwa, and iiwa_stack's YAML) with
// the position trajectory controller its iiwa_gazebo.launch spawns.
TEST(RealRobots, RealIiwa14FollowsAPositionTrajectoryInItsNamespace) {
  const std::filesystem::path dir = real_robots() / "iiwa14";
  if (!std::filesystem::exists(dir / "urdf/iiwa14_primitive_collision.urdf"))
    GTEST_SKIP() << "no " << dir.string() << " (set LCM_CONTROL_REAL_ROBOTS to the robots folder)";
  launch_real_robot("iiwa14",
                    "urdf: " + (dir / "urdf/iiwa14_primitive_collision.urdf").string() + "\nconfig: " +
                        (dir / "config/iiwa_control.yaml").string() +
                        "\ncontrollers: [joint_state_controller, PositionJointInterface_trajectory_controller]\n",
                    "started joint_state_controller, PositionJointInterface_trajectory_controller",
                    (dir / "pkgs").string(), [&](const std::string& url) {
                      lt::ChildProcess send({lt::bin("send-trajectory"), "--namespace", "iiwa", "--lcm-url", url,
                                             "PositionJointInterface_trajectory_controller", "--point",
                                             "3:0.3,0.3,0.3,-0.3,0.3,0.3,0.3"});
                      ASSERT_EQ(send.wait(40), 0) << send.output();
                      EXPECT_NE(send.output().find("SUCCEEDED"), std::string::npos) << send.output();
                    });
}

// The real rrbot of the Gazebo ros_control tutorial (namespace /rrbot, its YAML nested under rrbot:), each joint under
// its effort JointPositionController (p 100, d 10).
TEST(RealRobots, RealRrbotJointsGoWhereTheirPositionControllersAreTold) {
  const std::filesystem::path dir = real_robots() / "rrbot";
  if (!std::filesystem::exists(dir / "urdf/rrbot.urdf"))
    GTEST_SKIP() << "no " << dir.string() << " (set LCM_CONTROL_REAL_ROBOTS to the robots folder)";
  launch_real_robot(
      "rrbot",
      "urdf: " + (dir / "urdf/rrbot.urdf").string() + "\nconfig: " + (dir / "config/rrbot_control.yaml").string() +
          "\ncontrollers: [joint_state_controller, joint1_position_controller, joint2_position_controller]\n",
      "started joint_state_controller, joint1_position_controller, joint2_position_controller", (dir / "pkgs").string(),
      [&](const std::string& url) {
        lcm::LCM lc(url);
        lt::Recorder<joint_state_t> states(lc, "rrbot/joint_states");
        ASSERT_TRUE(lt::pump_until(lc, [&] { return !states.messages.empty(); }, 10)) << "no rrbot/joint_states";
        const int64_t start = states.messages.back().utime;
        for (const char* c : {"joint1_position_controller", "joint2_position_controller"}) {
          lt::ChildProcess cmd({lt::bin("turret-cmd"), "--namespace", "rrbot", "--lcm-url", url, c, "0.5"});
          EXPECT_EQ(cmd.wait(15), 0) << cmd.output();
        }
        ASSERT_TRUE(lt::pump_until(lc, [&] { return states.messages.back().utime - start > 5'000'000; }, 30));
        // p 100 against the two 1 m links' weight (about 12 N*m at joint 1), with a tiny I (0.01): a steady error of
        // about 0.12 rad after 5 s, as Gazebo leaves it.
        EXPECT_NEAR(position_of(states.messages.back(), "joint1"), 0.5, 0.15);
        EXPECT_NEAR(position_of(states.messages.back(), "joint2"), 0.5, 0.15);
        EXPECT_LT(std::abs(velocity_of(states.messages.back(), "joint1")), 0.05);
      });
}

// The real Panda with franka_gazebo's three transmissions per joint, its start pose and the position trajectory
// controller (the guide's launch file).
TEST(RealRobots, RealPandaFollowsAPositionTrajectoryFromFrankasStartPose) {
  const std::filesystem::path dir = real_robots() / "panda";
  if (!std::filesystem::exists(dir / "urdf/panda.urdf"))
    GTEST_SKIP() << "no " << dir.string() << " (set LCM_CONTROL_REAL_ROBOTS to the robots folder)";
  launch_real_robot(
      "panda",
      "urdf: " + (dir / "urdf/panda.urdf").string() + "\nconfig: " + (dir / "config/sim_controllers.yaml").string() +
          "\nargs: {arm_id: panda}\ninitial_positions: {panda_joint2: -0.785, panda_joint4: -2.356, panda_joint6: "
          "1.571, panda_joint7: 0.785}\ncontrollers: [franka_state_controller, position_joint_trajectory_controller]\n",
      "started franka_state_controller, position_joint_trajectory_controller", (dir / "pkgs").string(),
      [&](const std::string& url) {
        lt::ChildProcess send({lt::bin("send-trajectory"), "--lcm-url", url, "position_joint_trajectory_controller",
                               "--point", "3:0.3,-0.5,0.3,-2.0,0.3,1.8,0.5"});
        ASSERT_EQ(send.wait(40), 0) << send.output();
        EXPECT_NE(send.output().find("SUCCEEDED"), std::string::npos) << send.output();
      });
}

// Still while holding, its goal SUCCEEDED, still again, each joint at its goal: a light upright arm under
// franka_gazebo's stiffest gains, where an explicit D term chattered at the velocity limit every step.
void stiff_arm_holds_and_reaches(Session& s, const std::string& controller) {
  ASSERT_NO_FATAL_FAILURE(s.start({"joint_state_controller", controller}));
  EXPECT_LT(worst_speed(s, 1.0), 0.05) << s.sim_output();
  std::string out;
  ASSERT_EQ(s.send({controller, "--point", "2:0.3,0.3,-0.3,0.3"}, out), 0) << out << s.sim_output();
  EXPECT_NE(out.find(controller + ": SUCCEEDED"), std::string::npos) << out;
  EXPECT_LT(worst_speed(s, 1.0), 0.05);
  const joint_state_t end = latest_state(s);
  EXPECT_NEAR(position_of(end, "joint1"), 0.3, 0.01);
  EXPECT_NEAR(position_of(end, "joint2"), 0.3, 0.01);
  EXPECT_NEAR(position_of(end, "joint3"), -0.3, 0.01);
  EXPECT_NEAR(position_of(end, "joint4"), 0.3, 0.01);
}
}  // namespace

// Issue 30, item 5, with the PID in the simulator (gazebo_ros_control pid_gains): it applies the D term
// implicitly.
TEST(RealRobots, LightUprightArmUnderStiffGainsHoldsStillAndReachesItsGoal) {
  Session s(lt::source("test/e2e/data/stiff_arm.urdf.xacro"), lt::source("test/e2e/data/stiff_arm.yaml"), {});
  stiff_arm_holds_and_reaches(s, "arm_controller");
}

// The same gains in an effort JointTrajectoryController (franka_gazebo's effort_joint_trajectory_controller): its
// commands say how much damping they hold, and the simulator applies that part implicitly.
TEST(RealRobots, LightUprightArmUnderStiffEffortTrajectoryGainsHoldsStillAndReachesItsGoal) {
  Session s(lt::source("test/e2e/data/stiff_arm.urdf.xacro"), lt::source("test/e2e/data/stiff_arm_effort.yaml"),
            {"--xacro-arg", "interface:=EffortJointInterface"});
  stiff_arm_holds_and_reaches(s, "arm_controller");
}

// The real Franka Panda from ../shared/robots (franka_gazebo's files, effort transmissions only), upright under its
// own effort_joint_trajectory_controller gains, when the checkout has them: joints 1, 3, 5 and 7 flipped at their
// velocity limits every step before.
TEST(RealRobots, RealPandaUprightUnderItsOwnEffortGainsHoldsStillAndReachesItsGoal) {
  const std::filesystem::path dir = real_robots();
  if (!std::filesystem::exists(dir / "panda/urdf/panda_effort_only.urdf"))
    GTEST_SKIP() << "no " << (dir / "panda").string() << " (set LCM_CONTROL_REAL_ROBOTS to the robots folder)";
  Session s((dir / "panda/urdf/panda_effort_only.urdf").string(),
            (dir / "panda/config/sim_controllers.panda.yaml").string(),
            {"--package-path", (dir / "panda/pkgs").string(), "--arg", "arm_id=panda"});
  ASSERT_NO_FATAL_FAILURE(s.start({"franka_state_controller", "effort_joint_trajectory_controller"}));
  // Its first 0.3 s settle the spawn: joint 4 starts at its -0.07 limit, and at joint 6 = 0 the wrist's collision
  // meshes touch (self_collide is on, as franka_gazebo has it), which pushes joint 6 to 0.11 against its 12 N*m.
  worst_speed(s, 1.0);
  EXPECT_LT(worst_speed(s, 1.0), 0.05) << s.sim_output();
  std::string out;
  // To franka_gazebo's start pose.
  ASSERT_EQ(s.send({"effort_joint_trajectory_controller", "--point", "3:0,-0.785,0,-2.356,0,1.571,0.785"}, out), 0)
      << out << s.sim_output();
  EXPECT_NE(out.find("effort_joint_trajectory_controller: SUCCEEDED"), std::string::npos) << out;
  EXPECT_LT(worst_speed(s, 1.0), 0.05);
  const joint_state_t end = latest_state(s);
  EXPECT_NEAR(position_of(end, "panda_joint2"), -0.785, 0.05);
  EXPECT_NEAR(position_of(end, "panda_joint4"), -2.356, 0.05);
  EXPECT_NEAR(position_of(end, "panda_joint6"), 1.571, 0.05);
}

TEST(RealRobots, NamespacedRobotUnderLaunchRunsItsThreeControllersInItsNamespace) {
  const std::string dir = lt::temp_dir("ns_bot_launch");
  const std::string file = dir + "/ns_bot.launch.yaml";
  std::ofstream(file) << "urdf: " << robot("ns_bot.urdf") << "\nconfig: " << robot("ns_bot.yaml")
                      << "\ncontrollers: [joint_state_controller, joint1_position_controller, "
                         "joint2_position_controller]\n";
  const std::string url = lt::unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  lcm::LCM lc(url);
  ASSERT_TRUE(lc.good());
  lt::Recorder<joint_state_t> states(lc, "ns_bot/joint_states");

  // No --namespace anywhere: the URDF's <robotNamespace>/ns_bot</robotNamespace> decides, for launch too.
  lt::ChildProcess launch({lt::bin("launch"), file, "--lcm-url", url, "--stop-timeout", "20"});
  ASSERT_TRUE(launch.wait_for_output("started joint_state_controller, joint1_position_controller, "
                                     "joint2_position_controller",
                                     40))
      << launch.output();
  EXPECT_NE(launch.output().find("controllers read from 'ns_bot:', the robot's namespace"), std::string::npos)
      << launch.output();

  lt::ChildProcess list({lt::bin("cmctl"), "--namespace", "ns_bot", "list"}, env);
  ASSERT_EQ(list.wait(15), 0) << list.output();
  for (const char* c : {"joint_state_controller", "joint1_position_controller", "joint2_position_controller"})
    EXPECT_NE(list.output().find(c), std::string::npos) << list.output();

  ASSERT_TRUE(lt::pump_until(lc, [&] { return !states.messages.empty(); }, 10)) << "no ns_bot/joint_states";
  const joint_state_t before = states.messages.back();
  EXPECT_NEAR(position_of(before, "joint1"), 0.0, 0.01);
  lt::ChildProcess cmd({lt::bin("turret-cmd"), "--namespace", "ns_bot", "joint1_position_controller", "0.5"}, env);
  EXPECT_EQ(cmd.wait(15), 0) << cmd.output();
  // Three seconds of sim time later joint1 has settled near 0.5 (p 100 against the arm's weight, i_clamp 1: as
  // in Gazebo, a steady error of about 0.1 rad remains).
  ASSERT_TRUE(lt::pump_until(
      lc, [&] { return states.messages.back().utime - before.utime > 3'000'000 + 1'000'000; }, 20));
  const joint_state_t after = states.messages.back();
  EXPECT_NEAR(position_of(after, "joint1"), 0.55, 0.07);
  EXPECT_NEAR(velocity_of(after, "joint1"), 0.0, 0.01);
  EXPECT_EQ(launch.stop(30), 0) << launch.output();
}

// Issue 30, item 4: a four-wheel base from its ROS launch file, which spawn_model puts at x 1, y 2, yaw 0.5 without
// -z (its origin is on the wheel axles, so its wheels start 5 cm inside the ground). As Gazebo, launch leaves it free
// (its root is not welded to `world`) at that pose; it rests on its wheels when launch says it is up, never thrown,
// and it drives.
TEST(RealRobots, MobileBaseFromItsLaunchFileRestsWhereSpawnModelPutsItAndDrives) {
  const std::string url = lt::unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  lcm::LCM lc(url);
  ASSERT_TRUE(lc.good());
  lt::Recorder<odometry_t> truth(lc, "sim_server/base_pose");
  lt::ChildProcess launch({lt::bin("launch"), robot("four_wheel_base.launch"), "--package-path", lt::source("test"),
                           "--lcm-url", url, "--stop-timeout", "20"});
  ASSERT_TRUE(launch.wait_for_output("started joint_state_controller, base_controller", 40)) << launch.output();
  EXPECT_NE(launch.output().find("the root link 'base_link' has no joint to `world`: a free base"), std::string::npos)
      << launch.output();
  EXPECT_NE(launch.output().find("floating base starts lifted by 0.05"), std::string::npos) << launch.output();
  // Every pose since sim_server started: never above its rest height by more than 2 cm.
  ASSERT_TRUE(lt::pump_until(lc, [&] { return truth.messages.size() >= 20; }, 10)) << "no sim_server/base_pose";
  double max_z = 0;
  for (const odometry_t& m : truth.messages) max_z = std::max(max_z, m.position.z);
  const odometry_t up = truth.messages.back();
  EXPECT_LT(max_z, 0.07);
  EXPECT_NEAR(up.position.x, 1.0, 1e-3);
  EXPECT_NEAR(up.position.y, 2.0, 1e-3);
  EXPECT_NEAR(up.position.z, 0.05, 2e-3);
  EXPECT_NEAR(up.yaw, 0.5, 1e-3);
  EXPECT_LT(std::hypot(up.linear.x, up.linear.y, up.linear.z), 0.01);
  // 0.2 m/s for 2 s along its heading.
  lt::ChildProcess drive({lt::bin("drive"), "base_controller", "0.2", "0", "--duration", "2"}, env);
  EXPECT_EQ(drive.wait(20), 0) << drive.output();
  ASSERT_TRUE(lt::pump_until(lc, [&] { return truth.messages.back().utime > up.utime + 3'000'000; }, 10));
  const odometry_t end = truth.messages.back();
  const double along = (end.position.x - up.position.x) * std::cos(0.5) + (end.position.y - up.position.y) * std::sin(0.5);
  EXPECT_GT(along, 0.25) << "x " << end.position.x << " y " << end.position.y;
  EXPECT_NEAR(end.position.z, 0.05, 2e-3);
  EXPECT_EQ(launch.stop(30), 0) << launch.output();
}

// A ROS-Industrial-style arm (effort="0" on position joints without pid_gains) from its ROS launch file with two
// <rosparam> files: launch, sim_server and controller_manager take it with one warning per joint, and it follows a
// trajectory under the merged arm_controller.
TEST(RealRobots, IndustrialArmWithZeroEffortLimitsRunsFromItsLaunchFileAndTwoYamls) {
  const std::string url = lt::unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};
  lt::ChildProcess launch({lt::bin("launch"), robot("industrial_arm.launch"), "--package-path", lt::source("test"),
                           "--lcm-url", url, "--stop-timeout", "20"});
  ASSERT_TRUE(launch.wait_for_output("started joint_state_controller, arm_controller", 40)) << launch.output();
  const std::string warning = "industrial_arm.urdf: joint 'joint_1': <limit effort=\"0\"> ignored";
  EXPECT_NE(launch.output().find("sim_server"), std::string::npos);
  size_t said = 0;
  for (size_t at = launch.output().find(warning); at != std::string::npos; at = launch.output().find(warning, at + 1))
    ++said;
  EXPECT_EQ(said, 1u) << "once, by sim_server (launch starts controller_manager with --quiet-model):\n"
                      << launch.output();
  EXPECT_NE(launch.output().find("arm_controller/constraints/goal_time replaces the value from"), std::string::npos)
      << launch.output();
  lt::ChildProcess send({lt::bin("send-trajectory"), "arm_controller", "--point", "1.5:0.5,-0.4"}, env);
  ASSERT_EQ(send.wait(30), 0) << send.output() << launch.output();
  EXPECT_NE(send.output().find("arm_controller: SUCCEEDED"), std::string::npos) << send.output();
  lcm::LCM lc(url);
  lt::Recorder<joint_state_t> states(lc, "joint_states");
  ASSERT_TRUE(lt::pump_until(lc, [&] { return !states.messages.empty(); }, 10));
  EXPECT_NEAR(position_of(states.messages.back(), "joint_1"), 0.5, 0.01);
  EXPECT_NEAR(position_of(states.messages.back(), "joint_2"), -0.4, 0.01);
  EXPECT_EQ(launch.stop(30), 0) << launch.output();
}

// A vendor's gz fork and vendors' controller types (test/robots/vendor_arm.*): the plugin is a simulator (a note
// names the rule), each vendor type one warning in doctor (exit 0) unless --controllers starts it (exit 3), and
// launch starts the rest.
TEST(RealRobots, AVendorsGzForkAndVendorControllerTypesRunTheRest) {
  const std::string urdf = robot("vendor_arm.urdf"), yaml = robot("vendor_arm.yaml");
  lt::ChildProcess doctor({lt::bin("doctor"), "--urdf", urdf, "--config", yaml});
  EXPECT_EQ(doctor.wait(30), 0) << doctor.output();
  const std::string out = doctor.output();
  EXPECT_NE(out.find("hardware plugin 'franka_ign_ros2_control/IgnitionSystem' is a Gazebo/gz simulator system (class "
                     "IgnitionSystem): played as a simulator here"),
            std::string::npos)
      << out;
  for (const char* vendor : {"'picknik_twist_controller/PicknikTwistController' is not available here",
                             "'franka_robot_state_broadcaster/FrankaRobotStateBroadcaster' is not available here"}) {
    const size_t at = out.find(vendor);
    EXPECT_NE(at, std::string::npos) << out;
    EXPECT_EQ(out.find(vendor, at + 1), std::string::npos) << "one warning per type:\n" << out;
  }
  EXPECT_EQ(out.find("did you mean"), std::string::npos) << out;
  lt::ChildProcess asked({lt::bin("doctor"), "--urdf", urdf, "--config", yaml, "--controllers",
                          "joint_state_broadcaster,twist_controller"});
  EXPECT_EQ(asked.wait(30), 3) << asked.output();
  EXPECT_NE(asked.output().find("(and --controllers starts it)"), std::string::npos) << asked.output();

  const std::string url = lt::unique_lcm_url();
  lt::ChildProcess launch({lt::bin("launch"), "--urdf", urdf, "--config", yaml, "--lcm-url", url, "--mode",
                           "lockstep", "--duration", "1"});
  EXPECT_EQ(launch.wait(60), 0) << launch.output();
  EXPECT_NE(launch.output().find("started joint_state_broadcaster, arm_controller"), std::string::npos)
      << launch.output();
  EXPECT_NE(launch.output().find("note: not starting 'twist_controller'"), std::string::npos) << launch.output();
}
