// The real ROS 2 grippers of ../shared/ros2_robots (gz_ros2_control's mimic gripper, Robotiq's 2F-85) in Bullet:
// their mimic joints have no actuator and follow the commanded joint through the physical gear coupling, measured
// on the multibody itself (joint_states computes the mimics from their joint, so only this shows the coupling).
// Skipped when the folder is absent; test/sim_server/mimic_test.cpp covers the trait with the project's gripper.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "test/support/process.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

struct Follower {
  std::string joint;
  double multiplier, offset;
};

// Commands `leader` to each of `targets` in turn (position interface) for 3 s of sim time each; after each, the
// leader is at the target and every follower at multiplier * leader + offset, measured in Bullet.
void check_coupling(const RobotModel& model, const std::string& leader, const std::vector<Follower>& followers,
                    const std::vector<double>& targets) {
  Simulation sim(model, {}, model.initial_positions);
  const int a = sim.actuators().find_joint(leader);
  ASSERT_GE(a, 0) << leader;
  for (const Follower& f : followers) EXPECT_EQ(sim.actuators().find_joint(f.joint), -1) << f.joint << " has no actuator";
  const Multibody& body = sim.multibody();
  auto q = [&](const std::string& joint) {
    const int k = body.joint_index(joint);
    return k < 0 ? NAN : body.position(body.joints()[k].link);
  };
  for (const double target : targets) {
    SCOPED_TRACE(target);
    double worst = 0;
    run(sim, 3000, [&](int) { sim.actuators().set_command(a, kPos, target); },
        [&](int) {
          for (const Follower& f : followers)
            worst = std::max(worst, std::abs(q(f.joint) - (f.multiplier * q(leader) + f.offset)));
        });
    EXPECT_NEAR(q(leader), target, 2e-3);
    for (const Follower& f : followers) EXPECT_NEAR(q(f.joint), f.multiplier * q(leader) + f.offset, 1e-3) << f.joint;
    EXPECT_LT(worst, 0.02) << "the largest coupling error on the way";
  }
}

TEST(sim_ros2_mimic, GzMimicGripperLeftFingerFollowsTheRightOneInBullet) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/gz_gripper_mimic/pkgs/gz_ros2_control_demos";
  const RobotModel model = load_robot_model(pkg + "/urdf/test_gripper_mimic_joint_position.xacro.urdf",
                                            pkg + "/config/gripper_controller_position.yaml");
  check_coupling(model, "right_finger_joint", {{"left_finger_joint", 1, 0}}, {0.3, 0.1});
}

TEST(sim_ros2_mimic, Robotiq2f85FiveMimicJointsFollowTheKnuckleInBullet) {
  NEED_ROS2_ROBOTS(dir);
  const std::string r = dir + "/robotiq_2f85";
  LoadOptions options;
  options.package_path = {r + "/pkgs"};
  const RobotModel model = load_robot_model(r + "/derived/robotiq_2f_85_sim_gazebo.urdf.xacro",
                                            r + "/config/robotiq_controllers.yaml", options);
  check_coupling(model, "robotiq_85_left_knuckle_joint",
                 {{"robotiq_85_right_knuckle_joint", -1, 0},
                  {"robotiq_85_left_inner_knuckle_joint", 1, 0},
                  {"robotiq_85_right_inner_knuckle_joint", -1, 0},
                  {"robotiq_85_left_finger_tip_joint", -1, 0},
                  {"robotiq_85_right_finger_tip_joint", 1, 0}},
                 {0.5, 0.2});
}

}  // namespace
}  // namespace lcm_control::sim
