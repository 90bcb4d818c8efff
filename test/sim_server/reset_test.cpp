// Simulation::reset(): back to the start pose and step 0, a run after it
// repeating the first bit for bit, what the user set carried over, and a bad
// start pose refused with nothing changed.
#include <gtest/gtest.h>

#include <vector>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

// Positions, velocities and efforts of every actuator after each of `steps` steps of a PID chasing a sine.
std::vector<double> trajectory(Simulation& sim, int steps) {
  std::vector<double> out;
  const int n = sim.actuators().size();
  run(sim, steps, [&](int k) {
    for (int i = 0; i < n; ++i) {
      Actuators& act = sim.actuators();
      const int8_t mode = act.wire_mode(i);
      act.set_command(i, mode, mode == kPos ? 0.8 * std::sin(0.01 * k) : 0.5);
    }
  }, [&](int) {
    for (int i = 0; i < n; ++i) {
      const Actuators& act = sim.actuators();
      out.insert(out.end(), {act.position(i), act.velocity(i), act.effort(i)});
    }
  });
  return out;
}

TEST(sim_reset, ARunAfterAResetRepeatsTheFirstBitForBit) {
  Simulation sim(modes_bot(), {}, {{"j_pid", 0.2}});
  const std::vector<double> first = trajectory(sim, 700);
  EXPECT_EQ(sim.step_count(), 700);
  sim.reset();
  EXPECT_EQ(sim.step_count(), 0);
  EXPECT_EQ(sim.time_us(), 0);
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(sim.actuators().find_joint("j_pid")), 0.2);
  const std::vector<double> second = trajectory(sim, 700);
  ASSERT_EQ(first.size(), second.size());
  for (size_t k = 0; k < first.size(); ++k) ASSERT_EQ(first[k], second[k]) << "value " << k;  // bit for bit
}

TEST(sim_reset, NewStartPositionsAreMergedAndKeptForLaterResets) {
  Simulation sim(modes_bot(), {}, {{"j_pid", 0.2}});
  trajectory(sim, 50);
  EXPECT_TRUE(sim.reset({{"j_effort", 0.3}}).empty());
  const Actuators& a = sim.actuators();
  EXPECT_DOUBLE_EQ(a.joint_position(a.find_joint("j_pid")), 0.2);
  EXPECT_DOUBLE_EQ(a.joint_position(a.find_joint("j_effort")), 0.3);
  trajectory(sim, 50);
  sim.reset();
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(sim.actuators().find_joint("j_effort")), 0.3);
  EXPECT_EQ(sim.initial_positions().size(), 2u);
}

TEST(sim_reset, GainsBrakesAndALatchedEStopCarryOver) {
  Simulation sim(modes_bot(), {});
  const int pid = sim.actuators().find_joint("j_pid");
  PidGains g = sim.actuators().gains(pid);
  g.p *= 3;
  sim.actuators().set_gains(pid, g);
  sim.actuators().set_brakes(false);
  sim.actuators().set_e_stop(true);
  sim.reset();
  EXPECT_DOUBLE_EQ(sim.actuators().gains(pid).p, g.p);
  EXPECT_FALSE(sim.actuators().brakes());
  EXPECT_TRUE(sim.actuators().e_stop());
}

TEST(sim_reset, AStartOutsideTheLimitsIsClampedAndSaid) {
  Simulation sim(pendulum(), {});
  const std::vector<std::string> w = sim.reset({{"swing", 9.0}});
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("joint 'swing' would start at 9"), std::string::npos) << w[0];
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(sim.actuators().find_joint("swing")), 2.5);
}

TEST(sim_reset, ABadStartIsRefusedAndNothingChanges) {
  Simulation sim(pendulum(), {}, {{"swing", 0.4}});
  trajectory(sim, 20);
  const double q = sim.actuators().joint_position(0);
  try {
    sim.reset({{"swnig", 0.1}});
    FAIL() << "no error";
  } catch (const ModelError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'swing'"), std::string::npos) << e.what();
  }
  EXPECT_EQ(sim.step_count(), 20);
  EXPECT_EQ(sim.actuators().joint_position(0), q);
  sim.reset();
  EXPECT_DOUBLE_EQ(sim.actuators().joint_position(0), 0.4);
}

}  // namespace
}  // namespace lcm_control::sim
