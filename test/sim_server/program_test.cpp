// sim_server's run plan: what its flags and the robot's files decide before anything runs (rates, base, hardware,
// brakes), as sim_server logs and uses it.
#include <gtest/gtest.h>

#include "sim_server/program.hpp"
#include "test/sim_server/sim_test_support.hpp"

namespace lcm_control::sim {
namespace {

std::string source(const std::string& path) { return std::string(LCM_CONTROL_SOURCE_DIR) + "/" + path; }

RobotModel bumper_bot() {  // no joint to world; its ROS 2 YAML's update_rate is 100
  return load_robot_model(source("test/robots/mobile/bumper_bot.urdf.xacro"),
                          source("test/robots/mobile/bumper_bot_controllers.yaml"));
}
RobotModel drive_bot() {  // every <ros2_control> block names mock_components/GenericSystem
  return load_robot_model(source("test/controller_manager/data/drive_bot.urdf"),
                          source("test/controller_manager/data/drive_bot.yaml"));
}

bool has_note(const RunPlan& p, const std::string& part) {
  for (const auto& n : p.notes)
    if (n.find(part) != std::string::npos) return true;
  return false;
}

TEST(SimProgram, AYamlsUpdateRateIsTheControlRateUnlessTheFlagsSayOtherwise) {
  const RobotModel model = bumper_bot();
  ProgramFlags f;
  RunPlan p = plan_run(f, model);
  EXPECT_EQ(p.rates.control_hz, 100);
  EXPECT_EQ(p.rates.physics_hz, 1000);
  EXPECT_EQ(p.clock_every, 1);  // 100 Hz of clock at 100 Hz of control
  EXPECT_TRUE(has_note(p, "control rate 100 Hz from controller_manager's update_rate (physics 1000 Hz)"));
  f.control_hz = 500;
  p = plan_run(f, model);
  EXPECT_EQ(p.rates.control_hz, 500);
  EXPECT_EQ(p.rates.physics_hz, 1000);
  EXPECT_EQ(p.clock_every, 5);
  EXPECT_FALSE(has_note(p, "update_rate"));
  f.control_hz.reset();
  f.physics_hz = 2000;  // kept, the control rate still the YAML's
  p = plan_run(f, model);
  EXPECT_EQ(p.rates.control_hz, 100);
  EXPECT_EQ(p.rates.physics_hz, 2000);
  f.physics_hz = 1000;
  f.control_hz = 300;
  EXPECT_THROW(plan_run(f, model), std::invalid_argument);
}

TEST(SimProgram, ABaseWithNoJointToWorldIsFreeOnTheGroundWhereSpawnedUnlessWelded) {
  const RobotModel model = bumper_bot();
  ProgramFlags f;
  f.x = 1.5;
  f.yaw = 0.25;
  RunPlan p = plan_run(f, model);
  EXPECT_TRUE(p.world.floating_base);
  EXPECT_TRUE(p.world.ground);
  EXPECT_EQ(p.world.base_position.x(), 1.5);
  EXPECT_EQ(p.world.base_position.y(), 0);
  EXPECT_EQ(p.world.base_yaw, 0.25);
  EXPECT_TRUE(has_note(p, "has no joint to `world`: a free base on the ground plane")) << p.notes.front();
  f.fixed = true;
  p = plan_run(f, model);
  EXPECT_FALSE(p.world.floating_base);
  EXPECT_FALSE(p.world.ground);
  f.fixed = false;
  f.no_ground = true;
  p = plan_run(f, model);
  EXPECT_TRUE(p.world.floating_base);
  EXPECT_FALSE(p.world.ground);
  EXPECT_TRUE(p.brakes);
  f.no_brakes = true;
  EXPECT_FALSE(plan_run(f, model).brakes);
}

TEST(SimProgram, MockHardwareIsChosenByTheBlocksAndCannotFloat) {
  const RobotModel model = drive_bot();
  ProgramFlags f;
  RunPlan p = plan_run(f, model);
  EXPECT_TRUE(p.mock);
  EXPECT_FALSE(p.brakes);
  EXPECT_FALSE(p.world.floating_base);
  EXPECT_TRUE(has_note(p, "every <ros2_control> block names mock hardware"));
  f.floating = true;
  try {
    plan_run(f, model);
    ADD_FAILURE() << "a floating mock robot was planned";
  } catch (const CLI::ValidationError& e) {
    EXPECT_NE(std::string(e.what()).find("--floating-base: needs physics, and mock hardware has none"),
              std::string::npos)
        << e.what();
  }
  f.physics = true;  // the same blocks simulated in Bullet: a floating base is then possible
  p = plan_run(f, model);
  EXPECT_FALSE(p.mock);
  EXPECT_TRUE(p.world.floating_base);
}

TEST(SimProgram, InitialPositionsFromTheBlocksThenTheFlags) {
  const RobotModel model = testing::turret();
  ProgramFlags f;
  f.initial = {"j2=0.5"};
  f.base_pose = {0.1, 0.2, 0.3, 0.4};
  f.fixed = true;  // turret_bot's launch file bolts it down: it has no joint to `world`
  const RunPlan p = plan_run(f, model);
  EXPECT_EQ(p.start.at("j2"), 0.5);
  EXPECT_EQ(p.start.count("j1"), 0u);  // not given: sim_server's 0
  EXPECT_FALSE(p.world.floating_base);
  EXPECT_EQ(p.world.base_position.z(), 0.3);
  EXPECT_EQ(p.world.base_yaw, 0.4);
}

}  // namespace
}  // namespace lcm_control::sim
