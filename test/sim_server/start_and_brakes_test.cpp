// What holds a robot before its controllers do: the initial pose (given, or
// clamped into the limits), the brakes on uncommanded effort joints, and each
// joint's own velocity limit.
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const auto& l : lines) s += l + "\n";
  return s;
}

TEST(sim_start, InitialPositionIsWhereTheJointStarts) {
  Simulation sim(pendulum(), {}, {{"swing", 1.0}});
  const int i = sim.actuators().find_joint("swing");
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(i), 1.0);
  EXPECT_TRUE(sim.multibody().start_warnings().empty()) << joined(sim.multibody().start_warnings());
}

TEST(sim_start, AStartOutsideTheLimitsIsClampedWithOneWarning) {
  Simulation sim(pendulum(), {}, {{"swing", 3.0}});
  const int i = sim.actuators().find_joint("swing");
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(i), 2.5);
  const std::string w = joined(sim.multibody().start_warnings());
  EXPECT_NE(w.find("joint 'swing' would start at 3, outside its limits [-2.5, 2.5]"), std::string::npos) << w;
  EXPECT_NE(w.find("--initial-position swing=VALUE"), std::string::npos) << w;
}

TEST(sim_start, ADefaultStartOutsideTheLimitsIsClampedToo) {
  // Like Franka's joint4, whose limits [-3.07, -0.07] exclude 0.
  RobotModel m = pendulum();
  for (auto& j : m.joints)
    if (j.name == "swing") j.lower = -2.0, j.upper = -0.5;
  Simulation sim(m, {});
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(sim.actuators().find_joint("swing")), -0.5);
  EXPECT_NE(joined(sim.multibody().start_warnings()).find("(no initial position given)"), std::string::npos);
}

TEST(sim_start, AnInitialPositionNamingNoMovingJointIsRefused) {
  try {
    Simulation sim(pendulum(), {}, {{"swnig", 0.1}});
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("joint 'swnig'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("did you mean 'swing'?"), std::string::npos) << e.what();
  }
  try {
    Simulation sim(pendulum(), {}, {{"mount_to_pivot", 0.1}});
    FAIL() << "accepted";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("it is a fixed joint"), std::string::npos) << e.what();
  }
}

TEST(sim_start, InitialPositionFlagsParseAndSayWhatIsWrong) {
  EXPECT_EQ(parse_initial_position("panda_joint4=-2.0"), (std::pair<std::string, double>{"panda_joint4", -2.0}));
  EXPECT_EQ(parse_initial_position("j:=0.5"), (std::pair<std::string, double>{"j", 0.5}));
  for (const char* bad : {"j=abc", "j=1.0x", "j=", "j=nan", "j"}) {
    try {
      parse_initial_position(bad);
      ADD_FAILURE() << bad << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(sim_brakes, AnUncommandedEffortJointHoldsItsStartAgainstGravity) {
  Simulation sim(pendulum(), {}, {{"swing", 1.0}});
  const int i = sim.actuators().find_joint("swing");
  run(sim, 2000, {});
  EXPECT_NEAR(sim.actuators().joint_position(i), 1.0, 1e-6);
  // The brake carries the bob's weight (2 kg about 0.5 m out): its torque shows as the joint's effort.
  EXPECT_GT(std::abs(sim.actuators().joint_effort(i)), 5.0);
}

TEST(sim_brakes, TheFirstCommandReleasesTheBrake) {
  Simulation sim(pendulum(), {}, {{"swing", 1.0}});
  const int i = sim.actuators().find_joint("swing");
  run(sim, 300, [&](int) { sim.actuators().set_command(i, kEff, 0.0); });
  EXPECT_LT(sim.actuators().joint_position(i), 0.8);  // falls freely
}

TEST(sim_brakes, TheWatchdogBrakesAndTheEStopDoesNot) {
  Simulation sim(pendulum(), {}, {{"swing", 1.0}});
  Actuators& act = sim.actuators();
  const int i = act.find_joint("swing");
  run(sim, 100, [&](int) { act.set_command(i, kEff, 0.0); });
  act.set_hold_all(true);
  const double held = act.joint_position(i);
  run(sim, 1000, {});
  EXPECT_NEAR(act.joint_position(i), held, 0.05);  // stopped within the effort limit, then held
  const double stopped = act.joint_position(i);
  run(sim, 500, {});
  EXPECT_NEAR(act.joint_position(i), stopped, 1e-6);
  act.set_hold_all(false);
  act.set_e_stop(true);
  run(sim, 300, {});
  EXPECT_LT(act.joint_position(i), stopped - 0.1);  // e-stop: effort 0, the pendulum swings
}

TEST(sim_brakes, WithoutBrakesAnUncommandedJointIsLimpAsInGazebo) {
  Simulation sim(pendulum(), {}, {{"swing", 1.0}});
  sim.actuators().set_brakes(false);
  run(sim, 300, {});
  EXPECT_LT(sim.actuators().joint_position(sim.actuators().find_joint("swing")), 0.8);
}

TEST(sim_velocity, EachJointKeepsItsOwnVelocityLimit) {
  Simulation sim(load_robot_model(data("two_speeds.urdf"), ""), {});
  Actuators& act = sim.actuators();
  const int slow = act.find_joint("slow"), fast = act.find_joint("fast");
  double slow_peak = 0, fast_peak = 0;
  run(sim, 2000, [&](int) { act.set_command(slow, kEff, 10), act.set_command(fast, kEff, 10); },
      [&](int) {
        slow_peak = std::max(slow_peak, std::abs(act.joint_velocity(slow)));
        fast_peak = std::max(fast_peak, std::abs(act.joint_velocity(fast)));
      });
  EXPECT_LE(slow_peak, 1.0 + 1e-12);
  EXPECT_NEAR(slow_peak, 1.0, 1e-9);
  EXPECT_GT(fast_peak, 40.0);
  EXPECT_LE(fast_peak, 50.0 + 1e-12);
}

TEST(sim_gains, AbsurdGainsNeverMakeTheStateNonFinite) {
  Simulation sim(modes_bot(), {});
  Actuators& act = sim.actuators();
  const int pid = act.find_joint("j_pid"), vel = act.find_joint("j_vel_pid");
  PidGains g;
  g.p = 1e308;
  g.d = 1e308;
  ASSERT_TRUE(act.set_gains(pid, g));
  ASSERT_TRUE(act.set_gains(vel, g));
  run(sim, 500, [&](int k) {
    act.set_command(pid, kPos, k % 2 ? 4.0 : -4.0);
    act.set_command(vel, kVel, k % 2 ? 15.0 : -15.0);
  }, [&](int k) {
    for (int i = 0; i < act.size(); ++i)
      ASSERT_TRUE(std::isfinite(act.joint_position(i)) && std::isfinite(act.joint_velocity(i))) << k << " " << i;
  });
}

}  // namespace
}  // namespace lcm_control::sim
