// ROS 2 chaining (issue 49): a diff drive writing two velocity PIDs' reference interfaces ("<pid>/<dof>") on
// ros2_bot.urdf's wheels (data/chain_bot.yaml): the claims, the update order, chained mode, and the rules that keep
// a chain whole (followers loaded, started and kept running while a controller writes them).
#include <gtest/gtest.h>

#include <optional>

#include <string>
#include <vector>

#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/twist_t.hpp"
#include "test/controller_manager/rig.hpp"
#include "controllers/builtin.hpp"
#include "description/load.hpp"

using namespace lcm_control;
using lcm_control::testing::Rig;

namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

struct ChainRig : Rig {
  ChainRig()
      : Rig(cm::builtin_registry(), lcm_control::testing::data("ros2_bot.urdf"),
            lcm_control::testing::data("chain_bot.yaml")) {}
  bool running(const std::string& name) {
    for (const auto& s : cm->loop().slots())
      if (s->name == name) return s->running;
    return false;
  }
  cm::Reply set_state(const std::string& component, Lifecycle state) {
    std::optional<cm::Reply> got;
    cm->set_component_state(component, state, [&](const cm::Reply& r) { got = r; });
    for (int k = 0; k < 5 && !got; ++k) cycle();
    return got.value_or(cm::Reply{false, "no reply"});
  }
  const cm::Controller& controller(const std::string& name) {
    for (const auto& s : cm->loop().slots())
      if (s->name == name) return *s->controller;
    throw std::runtime_error(name + " not loaded");
  }
};

}  // namespace

TEST(Chaining, AFollowerMustBeLoadedFirstAndCannotBeUnloadedUnderItsWriter) {
  ChainRig rig;
  rig.cycle();
  cm::Reply r = rig.load("base");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "'pid_left/left_wheel'") && has(r.message, "load 'pid_left' first")) << r.message;
  ASSERT_TRUE(rig.load("pid_left").ok);
  ASSERT_TRUE(rig.load("pid_right").ok);
  r = rig.load("base");
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "pid_left/left_wheel")) << r.message;
  r = rig.cm->unload("pid_left");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "'base' claims its reference interface 'pid_left/left_wheel'; unload 'base' first"))
      << r.message;
  // The writer updates before its followers, whatever the load order.
  std::vector<std::string> order;
  for (const cm::ControllerSlot* s : rig.cm->loop().order()) order.push_back(s->name);
  EXPECT_EQ(order, (std::vector<std::string>{"base", "pid_left", "pid_right"}));
  ASSERT_TRUE(rig.cm->unload("base").ok);
  EXPECT_TRUE(rig.cm->unload("pid_left").ok);
}

// ROS 2's JTC command_joints: it claims the references named there and follows the state of `joints`; a list that
// does not match `joints` one to one is refused naming the key.
TEST(Chaining, ATrajectoryControllersCommandJointsAreClaimedOnePerJoint) {
  ChainRig rig;
  rig.cycle();
  for (const char* n : {"pid_left", "pid_right"}) ASSERT_TRUE(rig.load(n).ok) << n;
  cm::Reply r = rig.load("short_trajectory");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "short_trajectory/command_joints: 1 name(s) for 2 joint(s): give one per joint of "
                             "`joints`, in its order"))
      << r.message;
  r = rig.load("wheel_trajectory");
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "claims VelocityJointInterface on pid_left/left_wheel, pid_right/right_wheel")) << r.message;
  ASSERT_TRUE(rig.switch_({"wheel_trajectory", "pid_left", "pid_right"}, {}).ok);
  EXPECT_TRUE(rig.controller("pid_left").chained_mode());
  std::vector<std::string> order;
  for (const cm::ControllerSlot* s : rig.cm->loop().order()) order.push_back(s->name);
  EXPECT_EQ(order.front(), "wheel_trajectory") << "the writer first";
}

// A chain runs whole (ros2_control): when a member stops on a failure, or because its hardware component leaves
// active, the controllers that write its references stop with it, and the reply or log names them and why.
TEST(Chaining, AMemberStoppedByItsComponentTakesTheControllersAboveItAlong) {
  for (const bool error : {false, true}) {
    ChainRig rig;
    rig.cycle();
    for (const char* n : {"pid_left", "pid_right", "base"}) ASSERT_TRUE(rig.load(n).ok) << n;
    ASSERT_TRUE(rig.switch_({"base", "pid_left", "pid_right"}, {}).ok);
    rig.cycle(3);
    if (error) {
      rig.state.error_component = {"Ros2Bot"};
      rig.state.error_reason = {"wheel driver fault"};
      rig.state.num_component_errors = 1;
      rig.cycle(1);
    } else {
      const cm::Reply r = rig.set_state("Ros2Bot", Lifecycle::Inactive);
      ASSERT_TRUE(r.ok) << r.message;
      EXPECT_TRUE(has(r.message, "and the controllers chained above it [base] (they write its reference "
                                 "interfaces: a chain runs whole, as in ros2_control)"))
          << r.message;
    }
    EXPECT_FALSE(rig.running("pid_left")) << "its component left active";
    EXPECT_FALSE(rig.running("base")) << "it writes the stopped PIDs' references" << (error ? " (error)" : "");
    EXPECT_FALSE(rig.controller("pid_left").chained_mode());
  }
}

// The admittance controller's own checks, each naming its key: joints that are not the chain's, a tip not below
// the base, a sensor that is not there, a mass of 0.
TEST(Chaining, AnAdmittanceControllersBadParametersAreNamed) {
  auto load = [](const std::string& key, const std::string& yaml) {
    RobotModel m = load_robot_model(lcm_control::testing::source("test/robots/ft_arm.urdf"),
                                    lcm_control::testing::source("test/robots/ft_arm.yaml"));
    for (auto& c : m.controllers)
      if (c.name == "admittance_controller") c.params[key] = YAML::Load(yaml);
    Bus bus("memq://", "");
    cm::ControllerManager manager(m, bus, cm::builtin_registry());
    return manager.load("admittance_controller");
  };
  cm::Reply r = load("joints", "[joint1, joint3]");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "admittance_controller/joints: [joint1, joint3]: the moving joints from 'base_link' to "
                             "'tool' are [joint1, joint2, joint3], in that order"))
      << r.message;
  r = load("kinematics", "{base: tool, tip: link1}");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "link 'link1' is not below 'tool'")) << r.message;
  r = load("ft_sensor", "{name: elbow_ft}");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "declares no sensor 'elbow_ft'") && has(r.message, "wrist_ft")) << r.message;
  r = load("admittance", "{selected_axes: [1, 0, 0, 0, 0, 0], mass: [0, 1, 1, 1, 1, 1], damping_ratio: [1, 1, 1, 1, "
                         "1, 1], stiffness: [100, 1, 1, 1, 1, 1]}");
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "admittance/mass: axis 0: 0 kg: give a mass > 0")) << r.message;
}

TEST(Chaining, AChainStartsWholeRunsInChainedModeAndStopsWhole) {
  ChainRig rig;
  rig.cycle();
  for (const char* n : {"pid_left", "pid_right", "base"}) ASSERT_TRUE(rig.load(n).ok) << n;
  cm::Reply r = rig.switch_({"base"}, {});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "cannot start 'base': it writes the reference interfaces of 'pid_left', which would not "
                             "be running; start 'pid_left' too"))
      << r.message;
  r = rig.switch_({"pid_left", "pid_right", "base"}, {});
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(rig.controller("pid_left").chained_mode());
  EXPECT_TRUE(rig.controller("pid_right").chained_mode());
  EXPECT_FALSE(rig.controller("base").chained_mode());
  // Listed as ros2_control lists them: chainable or not, in chained mode or not, the reference interfaces exported.
  const std::vector<controller_info_t> listed = rig.cm->list();
  ASSERT_EQ(listed.size(), 3u);
  EXPECT_TRUE(listed[0].chainable);
  EXPECT_TRUE(listed[0].chained_mode);
  ASSERT_FALSE(listed[0].references.empty());
  EXPECT_EQ(listed[0].references[0], "pid_left/left_wheel/velocity");
  EXPECT_EQ(listed[0].num_references, static_cast<int32_t>(listed[0].references.size()));
  EXPECT_FALSE(listed[2].chainable);
  EXPECT_TRUE(listed[2].references.empty());

  // A twist on the diff drive turns the wheels through the PIDs: v = 0.5 m/s, w = 1 rad/s, radius 0.1 m,
  // separation 0.6 m: left (0.5 - 0.3) / 0.1 = 2 rad/s, right (0.5 + 0.3) / 0.1 = 8 rad/s.
  twist_t t{};
  t.linear.x = 0.5;
  t.angular.z = 1.0;
  rig.publish("base/cmd_vel", t);
  float64_array_t ignored{};
  ignored.size = 1;
  ignored.data = {-30.0};
  rig.publish("pid_left/command", ignored);  // chained: its own input is not read
  rig.cycle(1500);
  EXPECT_NEAR(rig.joint("left_wheel").velocity, 2.0, 0.06);
  EXPECT_NEAR(rig.joint("right_wheel").velocity, 8.0, 0.24);

  // A follower stops only with its writer; together they stop, and the PIDs leave chained mode.
  r = rig.switch_({}, {"pid_left"});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "cannot stop 'pid_left': 'base' writes its reference interfaces and would keep running; "
                             "stop 'base' too"))
      << r.message;
  r = rig.switch_({}, {"base", "pid_left", "pid_right"});
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_FALSE(rig.controller("pid_left").chained_mode());
}

// The followers alone run on their own references (not chained), and a controller that commands the wheels
// directly conflicts with them as with any claimant.
TEST(Chaining, FollowersRunAloneOnTheirOwnInputAndConflictsNameBoth) {
  ChainRig rig;
  rig.cycle();
  for (const char* n : {"pid_left", "pid_right", "loose_base"}) ASSERT_TRUE(rig.load(n).ok) << n;
  ASSERT_TRUE(rig.switch_({"pid_left"}, {}).ok);
  EXPECT_FALSE(rig.controller("pid_left").chained_mode());
  float64_array_t ref{};
  ref.size = 1;
  ref.data = {3.0};
  rig.publish("pid_left/command", ref);
  rig.cycle(1500);
  EXPECT_NEAR(rig.joint("left_wheel").velocity, 3.0, 0.09);
  const cm::Reply r = rig.switch_({"loose_base"}, {});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "'pid_left'") && has(r.message, "'loose_base'") && has(r.message, "left_wheel"))
      << r.message;
}

// A chain adds no allocation to the cycle: a diff drive on two PIDs' references turning the wheels, and then a
// trajectory controller on the same references running a goal (its feedback and result published), 500 cycles each
// counted after warm-up.
TEST(Chaining, ChainedCyclesDoNotAllocate) {
  ChainRig rig;
  rig.commands.reserve(4000);
  rig.cycle();
  for (const char* n : {"joint_state_broadcaster", "pid_left", "pid_right", "base", "wheel_trajectory"})
    ASSERT_TRUE(rig.load(n).ok) << n;
  ASSERT_TRUE(rig.switch_({"joint_state_broadcaster", "pid_left", "pid_right", "base"}, {}).ok);
  twist_t t{};
  t.linear.x = 0.5;
  t.angular.z = 1.0;
  rig.publish("base/cmd_vel", t);
  rig.cycle(50);
  EXPECT_EQ(rig.allocations_in_cycles(500, true, false), 0) << "diff drive -> PIDs";
  EXPECT_TRUE(rig.controller("pid_left").chained_mode());

  ASSERT_TRUE(rig.switch_({"wheel_trajectory"}, {"base"}).ok);
  rig.publish("wheel_trajectory/command", lcm_control::testing::trajectory_goal(1, {"left_wheel", "right_wheel"},
                                                                               {{0.2, {0.2, -0.2}},
                                                                                {0.4, {0.4, -0.4}},
                                                                                {0.6, {0.6, -0.6}}}));
  rig.cycle(2);
  EXPECT_EQ(rig.allocations_in_cycles(500, true, false), 0) << "trajectory -> PIDs, the goal running and ending";
  EXPECT_TRUE(rig.controller("pid_left").chained_mode());
}
