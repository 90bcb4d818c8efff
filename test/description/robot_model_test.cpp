// turret_bot as loaded from config/: every figure the tutorial gives.
#include "description/robot_model.hpp"
#include "description/load.hpp"
#include "description/control_config.hpp"

#include <gtest/gtest.h>

#include "test/support/process.hpp"

using namespace lcm_control;
using lcm_control::testing::source;

class TurretBot : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    model_ = new RobotModel(load_robot_model(source("config/turret_bot.urdf"), source("config/turret_bot.yaml")));
  }
  static void TearDownTestSuite() { delete model_; }
  static RobotModel* model_;
};
RobotModel* TurretBot::model_ = nullptr;

TEST_F(TurretBot, Links) {
  const RobotModel& m = *model_;
  EXPECT_EQ(m.name, "turret_bot");
  EXPECT_EQ(m.root_link, "base");
  ASSERT_EQ(m.links.size(), 3u);

  const Link* base = m.link("base");
  ASSERT_TRUE(base && base->inertial);
  EXPECT_DOUBLE_EQ(base->inertial->mass, 16);
  EXPECT_TRUE(base->inertial->origin.translation().isApprox(Eigen::Vector3d(0, 0.5, 0)));
  EXPECT_DOUBLE_EQ(base->inertial->inertia(0, 0), 1.376);
  EXPECT_DOUBLE_EQ(base->inertial->inertia(1, 1), 0.317);
  EXPECT_DOUBLE_EQ(base->inertial->inertia(2, 2), 1.607);

  const Link* slider = m.link("slider");
  ASSERT_TRUE(slider && slider->inertial);
  EXPECT_DOUBLE_EQ(slider->inertial->mass, 9.8075);
  EXPECT_TRUE(slider->inertial->origin.translation().isApprox(Eigen::Vector3d(0, 0.05, 0.165)));
  EXPECT_DOUBLE_EQ(slider->inertial->inertia(0, 0), 0.15206);
  EXPECT_DOUBLE_EQ(slider->inertial->inertia(1, 1), 0.2293);
  EXPECT_DOUBLE_EQ(slider->inertial->inertia(2, 2), 0.09238);

  const Link* rotor = m.link("rotor");
  ASSERT_TRUE(rotor && rotor->inertial);
  EXPECT_DOUBLE_EQ(rotor->inertial->mass, 2.114);
  EXPECT_TRUE(rotor->inertial->origin.translation().isApprox(Eigen::Vector3d(0.13, 0, 0.03)));
  EXPECT_DOUBLE_EQ(rotor->inertial->inertia(0, 0), 0.00215);
  EXPECT_DOUBLE_EQ(rotor->inertial->inertia(1, 1), 0.02074);
  EXPECT_DOUBLE_EQ(rotor->inertial->inertia(2, 2), 0.02201);

  for (const Link& l : m.links) {
    EXPECT_EQ(l.collisions.size(), 1u) << l.name;
    EXPECT_EQ(l.inertial->inertia(0, 1), 0) << l.name;
  }
}

TEST_F(TurretBot, Joints) {
  const RobotModel& m = *model_;
  ASSERT_EQ(m.joints.size(), 2u);
  const Joint* j1 = m.joint("j1");
  ASSERT_TRUE(j1);
  EXPECT_EQ(j1->type, JointType::Prismatic);
  EXPECT_EQ(j1->parent_link, "base");
  EXPECT_EQ(j1->child_link, "slider");
  EXPECT_TRUE(j1->axis.isApprox(Eigen::Vector3d::UnitY()));
  EXPECT_TRUE(j1->has_position_limits);
  EXPECT_DOUBLE_EQ(j1->lower, 0);
  EXPECT_DOUBLE_EQ(j1->upper, 1);
  EXPECT_DOUBLE_EQ(j1->effort_limit, 1000);
  EXPECT_DOUBLE_EQ(j1->velocity_limit, 50);
  EXPECT_DOUBLE_EQ(j1->damping, 0.001);
  EXPECT_DOUBLE_EQ(j1->friction, 0.001);

  const Joint* j2 = m.joint("j2");
  ASSERT_TRUE(j2);
  EXPECT_EQ(j2->type, JointType::Revolute);
  EXPECT_EQ(j2->parent_link, "slider");
  EXPECT_EQ(j2->child_link, "rotor");
  EXPECT_TRUE(j2->origin.translation().isApprox(Eigen::Vector3d(0, 0.05, 0.475)));
  EXPECT_TRUE(j2->origin.linear().isApprox(Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(j2->axis.isApprox(Eigen::Vector3d::UnitZ()));
  EXPECT_DOUBLE_EQ(j2->lower, -3.14);
  EXPECT_DOUBLE_EQ(j2->upper, 3.14);
  EXPECT_DOUBLE_EQ(j2->effort_limit, 1000);
  EXPECT_DOUBLE_EQ(j2->velocity_limit, 50);
  EXPECT_DOUBLE_EQ(j2->damping, 0.001);
  EXPECT_DOUBLE_EQ(j2->friction, 0.001);
}

TEST_F(TurretBot, TransmissionsAndPlugin) {
  const RobotModel& m = *model_;
  ASSERT_EQ(m.transmissions.size(), 2u);
  EXPECT_EQ(m.transmissions[0].name, "t1");
  EXPECT_EQ(m.transmissions[0].joint, "j1");
  EXPECT_EQ(m.transmissions[0].actuator, "a1");
  EXPECT_EQ(m.transmissions[1].name, "t2");
  EXPECT_EQ(m.transmissions[1].joint, "j2");
  EXPECT_EQ(m.transmissions[1].actuator, "a2");
  for (const auto& t : m.transmissions) {
    EXPECT_EQ(t.type, "transmission_interface/SimpleTransmission");
    ASSERT_EQ(t.interfaces.size(), 1u);
    EXPECT_EQ(t.interfaces[0], Interface::Position);
    EXPECT_DOUBLE_EQ(t.map.reduction, 1);
    EXPECT_DOUBLE_EQ(t.map.offset, 0);
  }
  EXPECT_EQ(m.actuated_joints(), (std::vector<std::string>{"j1", "j2"}));
  EXPECT_TRUE(m.has_gazebo_ros_control_plugin);
}

TEST_F(TurretBot, ControllersAndGainsFromTheTutorialYaml) {
  const RobotModel& m = *model_;
  ASSERT_EQ(m.controllers.size(), 3u);
  EXPECT_EQ(m.controllers[0].name, "joint_state_controller");
  EXPECT_EQ(m.controllers[0].type, "joint_state_controller/JointStateController");
  EXPECT_EQ(m.controllers[0].params["publish_rate"].as<int>(), 60);
  EXPECT_EQ(m.controllers[1].name, "j1_controller");
  EXPECT_EQ(m.controllers[1].type, "position_controllers/JointPositionController");
  EXPECT_EQ(m.controllers[1].params["joint"].as<std::string>(), "j1");
  EXPECT_EQ(m.controllers[2].name, "j2_controller");
  EXPECT_EQ(m.controllers[2].params["joint"].as<std::string>(), "j2");

  ASSERT_EQ(m.pid_gains.size(), 2u);
  const PidGains& g1 = m.pid_gains.at("j1");
  EXPECT_DOUBLE_EQ(g1.p, 150);
  EXPECT_DOUBLE_EQ(g1.i, 0);
  EXPECT_DOUBLE_EQ(g1.d, 50);
  const PidGains& g2 = m.pid_gains.at("j2");
  EXPECT_DOUBLE_EQ(g2.p, 1);
  EXPECT_DOUBLE_EQ(g2.i, 0);
  EXPECT_DOUBLE_EQ(g2.d, 0.3);
  EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
}

TEST(ControlConfig, IClampVariantsAndAntiwindup) {
  RobotModel m;
  parse_control_config(m, YAML::Load(R"(
gazebo_ros_control:
  pid_gains:
    a: {p: 1, i: 2, d: 3, i_clamp: 4, antiwindup: true}
    b: {p: 1, i_clamp_min: 5, i_clamp_max: 6}
    c: {p: 1, i_clamp: 4, i_clamp_max: 7}
)"),
                       "x.yaml");
  EXPECT_DOUBLE_EQ(m.pid_gains["a"].i_clamp_min, -4);
  EXPECT_DOUBLE_EQ(m.pid_gains["a"].i_clamp_max, 4);
  EXPECT_TRUE(m.pid_gains["a"].antiwindup);
  EXPECT_DOUBLE_EQ(m.pid_gains["b"].i_clamp_min, -5);  // forced <= 0, as control_toolbox does
  EXPECT_DOUBLE_EQ(m.pid_gains["b"].i_clamp_max, 6);
  EXPECT_DOUBLE_EQ(m.pid_gains["c"].i_clamp_min, -4);
  EXPECT_DOUBLE_EQ(m.pid_gains["c"].i_clamp_max, 7);
}

TEST(Interfaces, WithAndWithoutPrefix) {
  EXPECT_EQ(parse_interface("hardware_interface/PositionJointInterface"), Interface::Position);
  EXPECT_EQ(parse_interface("  VelocityJointInterface\n "), Interface::Velocity);
  EXPECT_EQ(parse_interface("hardware_interface/EffortJointInterface"), Interface::Effort);
  EXPECT_FALSE(parse_interface("hardware_interface/JointStateInterface"));
  EXPECT_FALSE(parse_interface("PositionInterface"));
}

TEST(Doctor, PrintsTheModelAndExitsZero) {
  lcm_control::testing::ChildProcess p(
      {lcm_control::testing::bin("doctor"), "--urdf", source("config/turret_bot.urdf"), "--config",
       source("config/turret_bot.yaml")});
  EXPECT_EQ(p.wait(20), 0) << p.output();
  EXPECT_NE(p.output().find("position PID p 150 i 0 d 50"), std::string::npos) << p.output();
  EXPECT_NE(p.output().find("OK: 2 joints, 2 transmissions, 3 controllers"), std::string::npos);
}
