#include "controller_interface/registry.hpp"
#include "controllers/builtin.hpp"
#include "controller_manager/ros_catalog.hpp"

#include <gtest/gtest.h>

using namespace lcm_control::cm;

TEST(ControllerManagerRegistry, EveryBuiltinTypeCanBeCreated) {
  const auto& r = builtin_registry();
  EXPECT_EQ(r.types().size(), 37u);
  for (const auto& t : r.types()) EXPECT_NE(r.create(t), nullptr) << t;
  EXPECT_EQ(r.create("nope/Nope"), nullptr);
}

TEST(ControllerManagerRegistry, ClosestMatchByEditDistance) {
  const auto& r = builtin_registry();
  EXPECT_EQ(r.closest("position_controllers/JointPositionControler"), "position_controllers/JointPositionController");
  EXPECT_EQ(r.closest("effort_controller/JointEffortController"), "effort_controllers/JointEffortController");
  EXPECT_EQ(r.closest("JointStateController"), "joint_state_controller/JointStateController");
  const std::string m = unknown_type_message(r, "velocity_controllers/JointVelocityControler");
  EXPECT_NE(m.find("did you mean 'velocity_controllers/JointVelocityController'?"), std::string::npos) << m;
  for (const auto& t : r.types()) EXPECT_NE(m.find(t), std::string::npos) << t;
}

TEST(ControllerManagerRegistry, KnownRosTypesAreNotImplementedNeverMissing) {
  const auto& r = builtin_registry();
  for (const char* t : {"franka_example_controllers/ModelExampleController",
                        "four_wheel_steering_controller/FourWheelSteeringController",
                        "range_sensor_broadcaster/RangeSensorBroadcaster",
                        "franka_example_controllers/CartesianImpedanceExampleController"}) {
    const std::string m = unknown_type_message(r, t);
    const bool vendor = std::string(t).rfind("franka_", 0) == 0;
    EXPECT_NE(m.find(vendor ? "(a vendor's controller, franka_ros (Franka Emika)) is not available here"
                            : "is not implemented here"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("`cmctl list-types` lists the " + std::to_string(r.types().size()) + " implemented types"),
              std::string::npos)
        << m;
    EXPECT_EQ(m.find("does not exist"), std::string::npos) << m;
  }
  const std::string typo = unknown_type_message(r, "position_controllers/JointPositonController");
  EXPECT_NE(typo.find("does not exist; did you mean 'position_controllers/JointPositionController'?"),
            std::string::npos)
      << typo;
}

TEST(ControllerManagerRegistry, TheRos2TypesOfTheGzDemosAndUrAreBuiltIn) {
  const auto& r = builtin_registry();
  for (const char* t : {"joint_state_broadcaster/JointStateBroadcaster", "joint_trajectory_controller/JointTrajectoryController",
                        "forward_command_controller/ForwardCommandController",
                        "forward_command_controller/MultiInterfaceForwardCommandController",
                        "diff_drive_controller/DiffDriveController", "velocity_controllers/JointGroupVelocityController"}) {
    ASSERT_TRUE(r.has(t)) << t;
    EXPECT_NE(r.info(t)->ros, RosVersion::Ros1) << t;
  }
  EXPECT_EQ(r.info("joint_state_controller/JointStateController")->ros, RosVersion::Ros1);
}

TEST(ControllerManagerRegistry, TheTypesIiwaStackAndUrShipAreBuiltIn) {
  const auto& r = builtin_registry();
  for (const char* t : {"velocity_controllers/JointTrajectoryController", "effort_controllers/JointTrajectoryController",
                        "position_controllers/JointTrajectoryController", "effort_controllers/JointGroupPositionController",
                        "effort_controllers/JointGroupEffortController", "velocity_controllers/JointGroupVelocityController"})
    EXPECT_TRUE(r.has(t)) << t;
}

// One rule for types we do not implement: a misspelling of one we do (a few edits away) is an error with "did you
// mean"; any other package's type is not available here, never matched across packages.
TEST(ControllerManagerRegistry, AnotherPackagesTypeIsNotAvailableAndOnlyAMisspellingGetsDidYouMean) {
  const auto& r = builtin_registry();
  for (const char* t : {"picknik_twist_controller/PicknikTwistController",
                        "picknik_reset_fault_controller/PicknikResetFaultController",
                        "franka_robot_state_broadcaster/FrankaRobotStateBroadcaster", "acme_controllers/Welder"}) {
    EXPECT_FALSE(r.misspelling(t)) << t;
    const std::string m = unknown_type_message(r, t);
    EXPECT_NE(m.find("is not available here"), std::string::npos) << m;
    EXPECT_EQ(m.find("did you mean"), std::string::npos) << m;
  }
  const std::string m = unknown_type_message(r, "picknik_twist_controller/PicknikTwistController");
  EXPECT_NE(m.find("package 'picknik_twist_controller' is not one whose controllers this project implements"),
            std::string::npos)
      << m;
  for (const char* t : {"position_controllers/JointPositonController", "diff_drive_controller/DiffDriveControler",
                        "JointTrajectoryControler"}) {
    EXPECT_TRUE(r.misspelling(t)) << t;
    EXPECT_NE(unknown_type_message(r, t).find("does not exist; did you mean"), std::string::npos) << t;
  }
}

// The catalog keeps only what ROS has and this project does not: a type built in here is known by its declaration.
TEST(ControllerManagerRegistry, TheRosCatalogNamesNoBuiltinType) {
  const auto& r = builtin_registry();
  const std::vector<std::string> catalog = ros_catalog_types();
  EXPECT_GE(catalog.size(), 10u);
  for (const std::string& t : catalog) EXPECT_FALSE(r.has(t)) << t << " is built in: take it out of ros_catalog.cpp";
}
