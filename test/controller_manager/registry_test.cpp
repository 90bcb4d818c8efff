#include "controller_manager/registry.hpp"

#include <gtest/gtest.h>

using namespace lcm_control::cm;

TEST(ControllerManagerRegistry, EveryBuiltinTypeCanBeCreated) {
  const auto& r = builtin_registry();
  EXPECT_EQ(r.types().size(), 12u);
  for (const auto& t : r.types()) EXPECT_NE(r.create(t), nullptr) << t;
  EXPECT_EQ(r.create("nope/Nope"), nullptr);
}

TEST(ControllerManagerRegistry, ClosestMatchByEditDistance) {
  const auto& r = builtin_registry();
  EXPECT_EQ(r.closest("position_controllers/JointPositionControler"), "position_controllers/JointPositionController");
  EXPECT_EQ(r.closest("effort_controller/JointEffortController"), "effort_controllers/JointEffortController");
  EXPECT_EQ(r.closest("JointStateController"), "joint_state_controller/JointStateController");
  const std::string m = r.unknown_type_message("velocity_controllers/JointVelocityControler");
  EXPECT_NE(m.find("did you mean 'velocity_controllers/JointVelocityController'?"), std::string::npos) << m;
  for (const auto& t : r.types()) EXPECT_NE(m.find(t), std::string::npos) << t;
}

TEST(ControllerManagerRegistry, EditDistance) {
  EXPECT_EQ(edit_distance("", "abc"), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);
  EXPECT_EQ(edit_distance("same", "same"), 0u);
}
