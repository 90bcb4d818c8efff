// The real ROS 2 robots of ../shared/ros2_robots (never copied into the
// project): each expanded URDF loads with its controllers file as shipped, and
// the joints, interfaces, start pose and controllers are those its SOURCE.txt
// lists. Skipped when the shared folder is absent.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "test/support/process.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

std::string robots_dir() { return lt::ros2_robots_dir(); }

#define SKIP_WITHOUT_SHARED_ROBOTS() \
  if (robots_dir().empty()) GTEST_SKIP() << "no ../shared/ros2_robots (set LCM_CONTROL_ROS2_ROBOTS to the folder)"

struct Robot {
  std::string dir;  // <robots>/<name>
  RobotModel model;
};

// expected/<urdf> with @ROBOT_DIR@ replaced (in a temp copy), loaded with config/<yaml> and --package-path pkgs.
Robot load(const std::string& name, const std::string& urdf, const std::string& yaml,
           std::vector<std::pair<std::string, std::string>> args = {}) {
  Robot r;
  r.dir = robots_dir() + "/" + name;
  std::ifstream in(r.dir + "/expected/" + urdf);
  std::stringstream ss;
  ss << in.rdbuf();
  std::string text = ss.str();
  for (size_t at; (at = text.find("@ROBOT_DIR@")) != std::string::npos;) text.replace(at, 11, r.dir);
  const std::string copy = lt::temp_dir("ros2_real") + "/" + urdf;
  std::ofstream(copy) << text;
  LoadOptions o;
  o.package_path = {r.dir + "/pkgs"};
  o.args = std::move(args);
  r.model = load_robot_model(copy, yaml.empty() ? "" : r.dir + "/config/" + yaml, o);
  return r;
}

std::string load_error(const std::string& name, const std::string& urdf) {
  try {
    load(name, urdf, "");
  } catch (const ModelError& e) {
    return e.what();
  }
  return "";
}

std::vector<std::string> controller_names(const RobotModel& m) {
  std::vector<std::string> v;
  for (const auto& c : m.controllers) v.push_back(c.name);
  return v;
}

const std::vector<Interface> kPos{Interface::Position};
const std::vector<Interface> kPosVel{Interface::Position, Interface::Velocity};

}  // namespace

TEST(Ros2RealRobots, Ur5eInGzSim) {
  SKIP_WITHOUT_SHARED_ROBOTS();
  const Robot r = load("ur5e", "ur5e.urdf", "ur_controllers.yaml");
  const RobotModel& m = r.model;
  const std::vector<std::string> joints{"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                        "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  EXPECT_EQ(m.actuated_joints(), joints);
  for (const auto& t : m.transmissions) EXPECT_EQ(t.interfaces, kPosVel) << t.joint;
  ASSERT_EQ(m.ros2_control.size(), 1u);
  EXPECT_EQ(m.ros2_control[0].name, "ur");
  EXPECT_EQ(m.ros2_control[0].plugin, "gz_ros2_control/GazeboSimSystem");
  EXPECT_EQ(m.ros2_control[0].kind, HardwareKind::Simulator);
  EXPECT_EQ(m.initial_positions, (InitialPositions{{"shoulder_pan_joint", 0.0},
                                                   {"shoulder_lift_joint", -1.57},
                                                   {"elbow_joint", 0.0},
                                                   {"wrist_1_joint", -1.57},
                                                   {"wrist_2_joint", 0.0},
                                                   {"wrist_3_joint", 0.0}}));
  EXPECT_EQ(m.initial_velocities.size(), 6u);
  EXPECT_DOUBLE_EQ(m.joint("shoulder_pan_joint")->upper, 2 * M_PI);  // no min/max: the URDF limits stand
  EXPECT_EQ(m.update_rate_hz, 500.0);
  EXPECT_EQ(controller_names(m),
            (std::vector<std::string>{"joint_state_broadcaster", "io_and_status_controller",
                                      "speed_scaling_state_broadcaster", "force_torque_sensor_broadcaster",
                                      "joint_trajectory_controller", "scaled_joint_trajectory_controller",
                                      "forward_velocity_controller", "forward_position_controller"}));
  const ControllerSpec* jtc = m.controller("joint_trajectory_controller");
  EXPECT_EQ(jtc->type, "joint_trajectory_controller/JointTrajectoryController");
  EXPECT_EQ(jtc->params["joints"].size(), 6u);
  EXPECT_EQ(jtc->params["constraints"]["shoulder_lift_joint"]["goal"].as<double>(), 0.1);
  EXPECT_EQ(m.ros2_control_plugin.parameters,
            std::vector<std::string>{r.dir + "/pkgs/ur_simulation_gz/config/ur_controllers.yaml"});
}

TEST(Ros2RealRobots, GzCartPositionVelocityEffort) {
  SKIP_WITHOUT_SHARED_ROBOTS();
  const Robot pos = load("gz_cart", "test_cart_position.urdf", "cart_controller_position.yaml");
  EXPECT_EQ(pos.model.actuated_joints(), std::vector<std::string>{"slider_to_cart"});
  EXPECT_EQ(pos.model.transmissions[0].interfaces, kPos);
  EXPECT_EQ(pos.model.initial_positions, (InitialPositions{{"slider_to_cart", 5.0}}));
  EXPECT_EQ(pos.model.joint("slider_to_cart")->lower, -15.0);
  EXPECT_EQ(pos.model.update_rate_hz, 1000.0);
  EXPECT_EQ(controller_names(pos.model),
            (std::vector<std::string>{"joint_state_broadcaster", "joint_trajectory_controller"}));
  EXPECT_EQ(pos.model.controllers[1].type, "joint_trajectory_controller/JointTrajectoryController");  // in its section

  const Robot vel = load("gz_cart", "test_cart_velocity.urdf", "cart_controller_velocity.yaml");
  EXPECT_EQ(vel.model.transmissions.at(0).interfaces, std::vector<Interface>{Interface::Velocity});
  EXPECT_TRUE(vel.model.initial_positions.empty());
  EXPECT_EQ(vel.model.joint("slider_to_cart")->velocity_limit, 15.0);  // min/max -15..15 beat the URDF's 30
  ASSERT_EQ(vel.model.ros2_control[0].sensors.size(), 1u);
  EXPECT_EQ(vel.model.ros2_control[0].sensors[0].name, "cart_imu_sensor");
  EXPECT_EQ(vel.model.ros2_control[0].sensors[0].state_interfaces.size(), 10u);
  EXPECT_EQ(controller_names(vel.model),
            (std::vector<std::string>{"joint_state_broadcaster", "velocity_controller", "imu_sensor_broadcaster"}));
  EXPECT_EQ(vel.model.controller("imu_sensor_broadcaster")->params["frame_id"].as<std::string>(), "imu");

  const Robot eff = load("gz_cart", "test_cart_effort.urdf", "cart_controller_effort.yaml");
  EXPECT_EQ(eff.model.transmissions.at(0).interfaces, std::vector<Interface>{Interface::Effort});
  EXPECT_EQ(eff.model.initial_positions, (InitialPositions{{"slider_to_cart", 1.0}}));
  EXPECT_EQ(eff.model.controller("effort_controller")->type, "effort_controllers/JointGroupEffortController");
}

TEST(Ros2RealRobots, GzDiffDriveWithDottedLimits) {
  SKIP_WITHOUT_SHARED_ROBOTS();
  const Robot r = load("gz_diff_drive", "test_diff_drive.urdf", "diff_drive_controller_velocity.yaml");
  const RobotModel& m = r.model;
  EXPECT_EQ(m.actuated_joints(), (std::vector<std::string>{"left_wheel_joint", "right_wheel_joint"}));
  for (const auto& t : m.transmissions) EXPECT_EQ(t.interfaces, std::vector<Interface>{Interface::Velocity});
  EXPECT_EQ(m.joint("left_wheel_joint")->velocity_limit, 1.0);
  EXPECT_EQ(m.update_rate_hz, 100.0);
  const ControllerSpec* dd = m.controller("diff_drive_base_controller");
  ASSERT_TRUE(dd);
  EXPECT_EQ(dd->type, "diff_drive_controller/DiffDriveController");
  EXPECT_EQ(dd->params["linear"]["x"]["max_velocity"].as<double>(), 1.0);
  EXPECT_EQ(dd->params["angular"]["z"]["min_acceleration"].as<double>(), -1.0);
  EXPECT_EQ(dd->params["wheel_separation"].as<double>(), 1.25);
  EXPECT_EQ(dd->params["pose_covariance_diagonal"].size(), 6u);
}

TEST(Ros2RealRobots, GzGripperWithAMimicFinger) {
  SKIP_WITHOUT_SHARED_ROBOTS();
  for (const auto& [urdf, yaml, iface] :
       {std::tuple{"test_gripper_mimic_joint_position.urdf", "gripper_controller_position.yaml", Interface::Position},
        std::tuple{"test_gripper_mimic_joint_effort.urdf", "gripper_controller_effort.yaml", Interface::Effort}}) {
    const Robot r = load("gz_gripper_mimic", urdf, yaml);
    const RobotModel& m = r.model;
    EXPECT_EQ(m.actuated_joints(), std::vector<std::string>{"right_finger_joint"}) << urdf;
    EXPECT_EQ(m.transmissions.at(0).interfaces, std::vector<Interface>{iface}) << urdf;
    ASSERT_EQ(m.ros2_control.at(0).joints.size(), 2u);
    EXPECT_TRUE(m.ros2_control[0].joints[1].mimic) << urdf;
    ASSERT_TRUE(m.joint("left_finger_joint")->mimic);
    EXPECT_EQ(m.joint("left_finger_joint")->mimic->joint, "right_finger_joint");
    EXPECT_EQ(m.initial_positions, (InitialPositions{{"right_finger_joint", 0.15}})) << urdf;
    EXPECT_EQ(m.update_rate_hz, 100.0);
    EXPECT_EQ(m.controller("gripper_controller")->type, "forward_command_controller/ForwardCommandController");
  }
}

TEST(Ros2RealRobots, Robotiq2f85SimMockAndTheRealDriverRefused) {
  SKIP_WITHOUT_SHARED_ROBOTS();
  const Robot sim = load("robotiq_2f85", "robotiq_2f_85_sim_gazebo.urdf", "robotiq_controllers.yaml");
  EXPECT_EQ(sim.model.actuated_joints(), std::vector<std::string>{"robotiq_85_left_knuckle_joint"});
  EXPECT_EQ(sim.model.transmissions[0].interfaces, kPos);
  EXPECT_EQ(sim.model.ros2_control.at(0).joints.size(), 6u);
  size_t mimics = 0;
  for (const auto& j : sim.model.ros2_control[0].joints) mimics += j.mimic;
  EXPECT_EQ(mimics, 5u);
  EXPECT_EQ(sim.model.initial_positions, (InitialPositions{{"robotiq_85_left_knuckle_joint", 0.7929}}));
  EXPECT_EQ(sim.model.update_rate_hz, 500.0);
  EXPECT_EQ(controller_names(sim.model), (std::vector<std::string>{"joint_state_broadcaster", "robotiq_gripper_controller",
                                                                   "robotiq_activation_controller"}));
  EXPECT_EQ(sim.model.controller("robotiq_gripper_controller")->type,
            "parallel_gripper_action_controller/GripperActionController");

  const Robot view = load("robotiq_2f85", "robotiq_2f_85_view.urdf", "robotiq_controllers.yaml");
  const HardwareBlock& b = view.model.ros2_control.at(0);
  EXPECT_EQ(b.kind, HardwareKind::Mock);
  EXPECT_EQ(b.plugin, "mock_components/GenericSystem");
  ASSERT_EQ(b.gpios.size(), 1u);
  EXPECT_EQ(b.gpios[0].name, "reactivate_gripper");
  EXPECT_EQ(b.gpios[0].command_interfaces.size(), 2u);
  EXPECT_EQ(b.params.at(1), (std::pair<std::string, std::string>{"mock_sensor_commands", "False"}));

  EXPECT_NE(load_error("robotiq_2f85", "robotiq_2f_85_launch.urdf")
                .find(": ros2_control 'RobotiqGripperHardwareInterface': hardware plugin "
                      "'robotiq_driver/RobotiqGripperHardwareInterface' is neither a simulator nor mock hardware"),
            std::string::npos);
}

TEST(Ros2RealRobots, RrbotGazeboAndExample1YamlWithVar) {
  SKIP_WITHOUT_SHARED_ROBOTS();
  const Robot gz = load("rrbot9", "rrbot9_gazebo.urdf", "rrbot_controllers.yaml");
  EXPECT_EQ(gz.model.actuated_joints(), (std::vector<std::string>{"joint1", "joint2"}));
  for (const auto& t : gz.model.transmissions) EXPECT_EQ(t.interfaces, kPos);
  EXPECT_EQ(gz.model.ros2_control.at(0).joints[0].command_interface("position")->min, -1.0);
  EXPECT_FALSE(gz.model.joint("joint1")->has_position_limits);  // continuous: the command limit is kept on the interface
  EXPECT_EQ(gz.model.update_rate_hz, 1000.0);
  EXPECT_EQ(controller_names(gz.model), (std::vector<std::string>{"joint_state_broadcaster", "forward_position_controller"}));

  const Robot ex1 = load("rrbot9", "rrbot9_gazebo.urdf", "example_1/rrbot_controllers.yaml", {{"joint_prefix", "joint"}});
  EXPECT_FALSE(ex1.model.update_rate_hz);
  const ControllerSpec* fwd = ex1.model.controller("forward_position_controller");
  ASSERT_TRUE(fwd);
  EXPECT_EQ(fwd->params["joints"][1].as<std::string>(), "joint2");
  EXPECT_EQ(ex1.model.controller("joint_state_broadcaster")->params["update_rate"].as<int>(), 50);

  // ros2_control_demos' example hardware is played as mock hardware (example_1 runs with it, as a mock).
  for (const char* demo : {"rrbot9_mock.urdf", "rrbot1.urdf"}) {
    const Robot r = load("rrbot9", demo, "example_1/rrbot_controllers.yaml", {{"joint_prefix", "joint"}});
    ASSERT_EQ(r.model.ros2_control.size(), 1u) << demo;
    EXPECT_EQ(r.model.ros2_control[0].kind, HardwareKind::Mock) << demo;
  }
}
