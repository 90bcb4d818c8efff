// Hardware components as ros2_control's resource manager sees them: one per <ros2_control> block with what it owns,
// one named after a robot without blocks, the states hardware_components_initial_state starts them in, and the
// lifecycle transitions between states.
#include <gtest/gtest.h>

#include <fstream>

#include "description/hardware_components.hpp"
#include "test/support/process.hpp"
#include "description/load.hpp"

using namespace lcm_control;
namespace lt = lcm_control::testing;

namespace {

const std::string kArm = lt::source("test/robots/two_component_arm.urdf");
const std::string kArmYaml = lt::source("test/robots/two_component_arm.yaml");

std::string with_initial_state(const std::string& block) {
  const std::string dir = lt::temp_dir("initial_state");
  std::ifstream in(kArmYaml);
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  yaml.replace(yaml.find("    update_rate: 500\n"), 0, block);
  const std::string path = dir + "/arm.yaml";
  std::ofstream(path) << yaml;
  return path;
}

TEST(HardwareComponents, OnePerRos2ControlBlockWithWhatItOwns) {
  const RobotModel m = load_robot_model(kArm, kArmYaml);
  const auto c = hardware_components(m);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].name, "arm");
  EXPECT_EQ(c[0].type, "system");
  EXPECT_EQ(c[0].plugin, "gz_ros2_control/GazeboSimSystem");
  EXPECT_EQ(c[0].kind, "simulator");
  EXPECT_EQ(c[0].joints, (std::vector<std::string>{"shoulder", "elbow"}));
  EXPECT_EQ(c[0].actuators.size(), 2u);
  EXPECT_TRUE(c[0].sensors.empty());
  EXPECT_EQ(c[1].name, "gripper");
  EXPECT_EQ(c[1].type, "actuator");
  EXPECT_EQ(c[1].joints, (std::vector<std::string>{"finger_joint"}));
  EXPECT_EQ(c[2].name, "wrist");
  EXPECT_EQ(c[2].type, "sensor");
  EXPECT_TRUE(c[2].joints.empty());
  EXPECT_EQ(c[2].sensors, (std::vector<std::string>{"wrist_imu"}));
  EXPECT_EQ(initial_component_states(m, c),
            (std::vector<Lifecycle>{Lifecycle::Active, Lifecycle::Active, Lifecycle::Active}));
}

TEST(HardwareComponents, ARobotWithoutBlocksIsOneComponentNamedAfterIt) {
  const RobotModel m = load_robot_model(lt::source("config/turret_bot.urdf"), lt::source("config/turret_bot.yaml"));
  const auto c = hardware_components(m);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].name, m.name);
  EXPECT_EQ(c[0].plugin, "gazebo_ros_control/DefaultRobotHWSim");
  EXPECT_EQ(c[0].joints, (std::vector<std::string>{"j1", "j2"}));
}

TEST(HardwareComponents, InitialStatesAsAMapOrAsDottedKeys) {
  for (const std::string block :
       {"    hardware_components_initial_state:\n      unconfigured: [gripper]\n      inactive: [wrist]\n",
        "    hardware_components_initial_state.unconfigured: [gripper]\n"
        "    hardware_components_initial_state.inactive: [\"wrist\"]\n"}) {
    const RobotModel m = load_robot_model(kArm, with_initial_state(block));
    EXPECT_EQ(initial_component_states(m, hardware_components(m)),
              (std::vector<Lifecycle>{Lifecycle::Active, Lifecycle::Unconfigured, Lifecycle::Inactive}))
        << block;
  }
}

TEST(HardwareComponents, AnInitialStateForNoComponentNamesTheKeyAndTheComponents) {
  const std::string yaml =
      with_initial_state("    hardware_components_initial_state:\n      inactive: [gripper_hw]\n");
  const RobotModel m = load_robot_model(kArm, yaml);
  try {
    initial_component_states(m, hardware_components(m));
    FAIL() << "accepted a component that does not exist";
  } catch (const ModelError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(yaml + ": controller_manager/ros__parameters/hardware_components_initial_state/inactive: "
                               "'gripper_hw' is not a hardware component of " +
                        kArm + " (its components: arm, gripper, wrist)"),
              std::string::npos)
        << what;
  }
}

TEST(HardwareComponents, AnInitialStateOtherThanUnconfiguredOrInactiveIsRefusedNamingIt) {
  const std::string yaml = with_initial_state("    hardware_components_initial_state:\n      finalised: [arm]\n");
  try {
    load_robot_model(kArm, yaml);
    FAIL() << "accepted 'finalised'";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("hardware_components_initial_state/finalised: 'finalised' is not a state a "
                                         "component can start in (unconfigured or inactive"),
              std::string::npos)
        << e.what();
  }
}

TEST(HardwareComponents, TransitionsAreRos2ControlsLifecycleSteps) {
  using L = Lifecycle;
  using V = std::vector<std::string>;
  EXPECT_EQ(lifecycle_transitions(L::Unconfigured, L::Active), (V{"configure", "activate"}));
  EXPECT_EQ(lifecycle_transitions(L::Active, L::Unconfigured), (V{"deactivate", "cleanup"}));
  EXPECT_EQ(lifecycle_transitions(L::Active, L::Inactive), (V{"deactivate"}));
  EXPECT_EQ(lifecycle_transitions(L::Inactive, L::Active), (V{"activate"}));
  EXPECT_EQ(lifecycle_transitions(L::Inactive, L::Inactive), V{});
  EXPECT_EQ(lifecycle_transitions(L::Active, L::Finalized), (V{"deactivate", "shutdown"}));
  EXPECT_EQ(lifecycle_transitions(L::Unconfigured, L::Finalized), (V{"shutdown"}));
  EXPECT_FALSE(lifecycle_transitions(L::Finalized, L::Active).has_value());
  EXPECT_EQ(lifecycle_from("inactive"), L::Inactive);
  EXPECT_FALSE(lifecycle_from("Inactive").has_value());
  EXPECT_STREQ(to_string(L::Finalized), "finalized");
}

}  // namespace
