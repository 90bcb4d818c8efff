#include "controller_manager/switch_plan.hpp"

#include <gtest/gtest.h>

using namespace lcm_control::cm;
using lcm_control::Interface;

namespace {
struct Fixture {
  Claim j1{Interface::Position, {"j1"}, {}, {}}, j2{Interface::Position, {"j2"}, {}, {}}, none{std::nullopt, {"j1", "j2"}, {}, {}};
  std::vector<LoadedController> loaded{{"a", "running", &j1, {}},
                                       {"b", "initialized", &j1, {}},
                                       {"c", "initialized", &j2, {}},
                                       {"d", "stopped", &j2, {}},
                                       {"jsc", "running", &none, {}}};
};
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
}  // namespace

TEST(ControllerManagerSwitchPlan, StopAStartBOnOneJointIsFine) {
  Fixture f;
  const auto p = plan_switch(f.loaded, {"b"}, {"a"}, 2);
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_EQ(p.stop, std::vector<int>{0});
  EXPECT_EQ(p.start, std::vector<int>{1});
}

TEST(ControllerManagerSwitchPlan, ConflictIsRefusedWhateverTheStrictness) {
  Fixture f;
  for (int strictness : {1, 2}) {
    const auto p = plan_switch(f.loaded, {"b"}, {}, strictness);
    EXPECT_FALSE(p.ok);
    EXPECT_TRUE(has(p.message, "controllers 'a' and 'b' would both claim joint 'j1'")) << p.message;
  }
  const auto p = plan_switch(f.loaded, {"c", "d"}, {}, 1);
  EXPECT_TRUE(has(p.message, "controllers 'c' and 'd' would both claim joint 'j2'")) << p.message;
}

TEST(ControllerManagerSwitchPlan, StrictRefusesUnknownNotRunningAndAlreadyRunning) {
  Fixture f;
  auto p = plan_switch(f.loaded, {"zz"}, {}, 2);
  EXPECT_FALSE(p.ok);
  EXPECT_TRUE(has(p.message, "cannot start 'zz': it is not loaded (loaded: a, b, c, d, jsc)")) << p.message;
  p = plan_switch(f.loaded, {}, {"c"}, 2);
  EXPECT_FALSE(p.ok);
  EXPECT_TRUE(has(p.message, "cannot stop 'c': it is not running (state: initialized)")) << p.message;
  p = plan_switch(f.loaded, {"a"}, {}, 2);
  EXPECT_FALSE(p.ok);
  EXPECT_TRUE(has(p.message, "cannot start 'a': it is already running")) << p.message;
}

TEST(ControllerManagerSwitchPlan, BestEffortDropsThoseEntriesAndSaysSo) {
  Fixture f;
  const auto p = plan_switch(f.loaded, {"zz", "a", "c"}, {"d"}, 1);
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_EQ(p.start, std::vector<int>{2});
  EXPECT_TRUE(p.stop.empty());
  ASSERT_EQ(p.notes.size(), 3u);
}

// However many names are not loaded, they make one note of bounded size (issue 35, item 2).
TEST(ControllerManagerSwitchPlan, BestEffortSaysAllUnknownNamesInOneShortNote) {
  Fixture f;
  std::vector<std::string> start(1000, std::string(5000, 'q'));
  start.push_back("c");
  const auto p = plan_switch(f.loaded, start, {}, 1);
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_EQ(p.start, std::vector<int>{2});
  ASSERT_EQ(p.notes.size(), 1u);
  EXPECT_LT(p.notes[0].size(), 1000u) << p.notes[0];
  EXPECT_NE(p.notes[0].find("(and 995 more): not loaded"), std::string::npos) << p.notes[0];
}

TEST(ControllerManagerSwitchPlan, SameNameInBothListsAndBadStrictnessAreRefused) {
  Fixture f;
  EXPECT_FALSE(plan_switch(f.loaded, {"b"}, {"b"}, 1).ok);
  const auto p = plan_switch(f.loaded, {"c"}, {}, 7);
  EXPECT_FALSE(p.ok);
  EXPECT_TRUE(has(p.message, "strictness 7")) << p.message;
  const auto z = plan_switch(f.loaded, {"c"}, {}, 0);
  EXPECT_TRUE(z.ok);
  ASSERT_FALSE(z.notes.empty());
  EXPECT_TRUE(has(z.notes[0], "BEST_EFFORT"));
}
