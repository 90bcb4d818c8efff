// The simulated hardware on turret_bot (the tutorial's acceptance numbers) and
// on modes_bot (every actuator mode, transmissions, limits, e-stop, hold).
#include <gtest/gtest.h>

#include <cmath>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

constexpr int kJ1 = 0, kJ2 = 1;  // turret_bot actuators a1 (j1, prismatic), a2 (j2, revolute)

TEST(sim_turret, ModesFollowTransmissionsAndGains) {
  Simulation sim(turret(), {});
  ASSERT_EQ(sim.actuators().size(), 2);
  EXPECT_EQ(sim.actuators().name(kJ1), "a1");
  EXPECT_EQ(sim.actuators().mode(kJ1), ActuatorMode::PositionPid);
  EXPECT_EQ(sim.actuators().mode(kJ2), ActuatorMode::PositionPid);
  EXPECT_EQ(sim.actuators().gains(kJ1).p, 150);
  EXPECT_NE(sim.actuators().describe(kJ1).find("position PID"), std::string::npos);
}

TEST(sim_turret, J1PositionCommandSettlesWithin1mm) {
  Simulation sim(turret(), {});
  double worst_late = 0;
  run(sim, 15000, [&](int) {
    sim.actuators().set_command(kJ1, kPos, 0.5);
    sim.actuators().set_command(kJ2, kPos, 0.0);
  }, [&](int k) {
    if (k >= 10000) worst_late = std::max(worst_late, std::abs(sim.actuators().joint_position(kJ1) - 0.5));
  });
  std::printf("j1 -> 0.5: error %.3g m at 15 s, worst over 10..15 s %.3g m\n",
              std::abs(sim.actuators().joint_position(kJ1) - 0.5), worst_late);
  EXPECT_LT(worst_late, 1e-3);
}

TEST(sim_turret, J2PositionCommandReachesWithin10mrad) {
  Simulation sim(turret(), {});
  double worst_late = 0;
  run(sim, 8000, [&](int) {
    sim.actuators().set_command(kJ1, kPos, 0.0);
    sim.actuators().set_command(kJ2, kPos, 1.0);
  }, [&](int k) {
    if (k >= 5000) worst_late = std::max(worst_late, std::abs(sim.actuators().joint_position(kJ2) - 1.0));
  });
  std::printf("j2 -> 1.0: error %.3g rad at 8 s, worst over 5..8 s %.3g rad\n",
              std::abs(sim.actuators().joint_position(kJ2) - 1.0), worst_late);
  EXPECT_LT(worst_late, 0.01);
}

TEST(sim_turret, J1CommandPastTheLimitNeverCrossesItByMoreThan1mm) {
  Simulation sim(turret(), {});
  double highest = -1;
  run(sim, 5000, [&](int) {
    sim.actuators().set_command(kJ1, kPos, 2.0);
    sim.actuators().set_command(kJ2, kPos, 0.0);
  }, [&](int) { highest = std::max(highest, sim.actuators().joint_position(kJ1)); });
  std::printf("j1 -> 2.0 (limit 1.0): highest %.6f m\n", highest);
  EXPECT_LT(highest, 1.0 + 1e-3);
  EXPECT_GT(highest, 0.99);
}

TEST(sim_turret, J1StopsAtTheLimitEvenWhenDrivenHardIntoIt) {
  // Run-time gains far above the tutorial's: the PID saturates at 1000 N into the limit.
  Simulation sim(turret(), {});
  PidGains hard = sim.actuators().gains(kJ1);
  hard.p = 1e5;
  hard.d = 100;
  sim.actuators().set_gains(kJ1, hard);
  double highest = -1, lowest_effort = 0;
  run(sim, 3000, [&](int) { sim.actuators().set_command(kJ1, kPos, 2.0); }, [&](int) {
    highest = std::max(highest, sim.actuators().joint_position(kJ1));
    lowest_effort = std::max(lowest_effort, std::abs(sim.actuators().joint_effort(kJ1)));
  });
  EXPECT_LT(highest, 1.0 + 1e-3);
  EXPECT_DOUBLE_EQ(lowest_effort, 1000);
}

TEST(sim_turret, J2EffortNeverExceedsItsLimit) {
  Simulation sim(turret(), {});
  PidGains stiff = sim.actuators().gains(kJ2);
  stiff.p = 1e5;
  sim.actuators().set_gains(kJ2, stiff);
  double peak = 0;
  run(sim, 4000, [&](int k) { sim.actuators().set_command(kJ2, kPos, k < 2000 ? 3.0 : -3.0); }, [&](int) {
    peak = std::max(peak, std::abs(sim.actuators().joint_effort(kJ2)));
    ASSERT_LE(std::abs(sim.actuators().effort(kJ2)), 1000.0);
  });
  EXPECT_DOUBLE_EQ(peak, 1000);  // it did saturate
}

TEST(sim_turret, PositionCommandsAreRateLimitedByTheVelocityLimit) {
  Simulation sim(turret(), {});
  PidGains stiff = sim.actuators().gains(kJ2);
  stiff.p = 1e4;
  stiff.d = 100;
  sim.actuators().set_gains(kJ2, stiff);
  // 50 rad/s: a jump to 3 rad takes 60 steps of 1 ms, so after 20 steps the goal is 1 rad at most.
  run(sim, 20, [&](int) { sim.actuators().set_command(kJ2, kPos, 3.0); });
  EXPECT_LT(sim.actuators().joint_position(kJ2), 1.0 + 1e-6);
}

TEST(sim_turret, EStopHoldsJ1Within1mmUnderAContraryCommand) {
  Simulation sim(turret(), {});
  auto command = [&](double j1) {
    sim.actuators().set_command(kJ1, kPos, j1);
    sim.actuators().set_command(kJ2, kPos, 0.0);
  };
  run(sim, 6000, [&](int) { command(0.5); });  // settled: what moves after this is the e-stop's doing
  const double latched = sim.actuators().joint_position(kJ1);
  sim.actuators().set_e_stop(true);
  double worst = 0;
  run(sim, 5000, [&](int) { command(0.0); },
      [&](int) { worst = std::max(worst, std::abs(sim.actuators().joint_position(kJ1) - latched)); });
  std::printf("e-stop: j1 moved at most %.3g m from %.4f under a command of 0\n", worst, latched);
  EXPECT_LT(worst, 1e-3);
  sim.actuators().set_e_stop(false);
  run(sim, 5000, [&](int) { command(0.0); });
  EXPECT_LT(std::abs(sim.actuators().joint_position(kJ1)), 0.01);  // released: commands resume
}

TEST(sim_turret, NoCommandHoldsThePositionItHadWhenCommandsStopped) {
  Simulation sim(turret(), {});
  run(sim, 400, [&](int) {
    sim.actuators().set_command(kJ1, kPos, 1.0);
    sim.actuators().set_command(kJ2, kPos, 0.0);
  });
  const double when_stopped = sim.actuators().joint_position(kJ1);
  ASSERT_GT(when_stopped, 0.05);
  run(sim, 6000, [&](int) {
    sim.actuators().set_command(kJ1, kNone, 0.0);
    sim.actuators().set_command(kJ2, kNone, 0.0);
  });
  EXPECT_NEAR(sim.actuators().joint_position(kJ1), when_stopped, 2e-3);
  EXPECT_LT(std::abs(sim.actuators().joint_velocity(kJ1)), 1e-3);
}

TEST(sim_turret, WatchdogHoldOverridesCommands) {
  Simulation sim(turret(), {});
  run(sim, 400, [&](int) { sim.actuators().set_command(kJ1, kPos, 1.0); });
  sim.actuators().set_hold_all(true);
  const double when_held = sim.actuators().joint_position(kJ1);
  run(sim, 6000, [&](int) { sim.actuators().set_command(kJ1, kPos, 1.0); });
  EXPECT_NEAR(sim.actuators().joint_position(kJ1), when_held, 2e-3);
}

TEST(sim_turret, GainsChangedBetweenStepsActOnTheNextStep) {
  Simulation sim(turret(), {});
  run(sim, 100, [&](int) { sim.actuators().set_command(kJ2, kPos, 1.0); });
  // A step's effort is p*e + d*(e - e_before)/dt, with e the error at its start.
  auto error = [&] { return 1.0 - sim.actuators().joint_position(kJ2); };
  const double e0 = error();
  sim.step();
  const double e1 = error();
  sim.step();
  const PidGains old_gains = sim.actuators().gains(kJ2);
  EXPECT_NEAR(sim.actuators().joint_effort(kJ2), old_gains.p * e1 + old_gains.d * (e1 - e0) / 1e-3, 1e-9);
  PidGains g = old_gains;
  g.p = 20;
  g.d = 1;
  ASSERT_TRUE(sim.actuators().set_gains(kJ2, g));
  const double e2 = error();
  sim.step();
  const double with_new = g.p * e2 + g.d * (e2 - e1) / 1e-3;
  const double with_old = old_gains.p * e2 + old_gains.d * (e2 - e1) / 1e-3;
  EXPECT_NEAR(sim.actuators().joint_effort(kJ2), with_new, 1e-9);
  EXPECT_GT(std::abs(with_new - with_old), 0.1);
}

TEST(sim_turret, DirectModeJointsRefuseGains) {
  Simulation sim(modes_bot(), {});
  const int direct = sim.actuators().find_joint("j_direct");
  EXPECT_FALSE(sim.actuators().has_pid(direct));
  EXPECT_FALSE(sim.actuators().set_gains(direct, PidGains{}));
}

}  // namespace
}  // namespace lcm_control::sim
