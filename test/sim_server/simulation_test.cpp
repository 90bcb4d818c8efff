// Every actuator mode of modes_bot, transmissions (reduction 2, offset, -1),
// the physics/control rate split, determinism, and the cost of a step.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <fstream>
#include <memory>
#include <vector>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "test/support/process.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

struct ModesBot {
  Simulation sim{modes_bot(), {}};
  Actuators& act = sim.actuators();
  int pid = act.find_joint("j_pid"), direct = act.find_joint("j_direct"), wheel = act.find_joint("j_wheel"),
      vel_pid = act.find_joint("j_vel_pid"), effort = act.find_joint("j_effort");
};

TEST(sim_modes, ModesComeFromTheInterfaceAndThePresenceOfGains) {
  ModesBot b;
  EXPECT_EQ(b.act.mode(b.pid), ActuatorMode::PositionPid);
  EXPECT_EQ(b.act.mode(b.direct), ActuatorMode::PositionDirect);
  EXPECT_EQ(b.act.mode(b.wheel), ActuatorMode::VelocityMotor);
  EXPECT_EQ(b.act.mode(b.vel_pid), ActuatorMode::VelocityPid);
  EXPECT_EQ(b.act.mode(b.effort), ActuatorMode::Effort);
  EXPECT_EQ(b.act.wire_mode(b.wheel), kVel);
}

TEST(sim_modes, ReductionTwoActuatorCommandTwoMovesTheJointToOne) {
  ModesBot b;
  run(b.sim, 3000, [&](int) { b.act.set_command(b.pid, kPos, 2.0); });
  EXPECT_NEAR(b.act.joint_position(b.pid), 1.0, 1e-3);
  EXPECT_NEAR(b.act.position(b.pid), 2.0, 2e-3);  // reported in actuator units
}

TEST(sim_modes, DirectPositionFollowsTheCommandThroughReductionAndOffset) {
  ModesBot b;
  // joint = actuator / 2 + 0.1 = 0.3; the 2 m/s velocity limit rate-limits the goal to 2 mm per step,
  // which the joint follows exactly.
  run(b.sim, 500, [&](int) { b.act.set_command(b.direct, kPos, 0.4); },
      [&](int k) { ASSERT_NEAR(b.act.joint_position(b.direct), std::min(0.3, 0.002 * (k + 1)), 1e-9) << k; });
  EXPECT_NEAR(b.act.joint_position(b.direct), 0.3, 1e-9);
  EXPECT_NEAR(b.act.position(b.direct), 0.4, 1e-9);
  EXPECT_NEAR(b.act.joint_velocity(b.direct), 0.0, 1e-9);
}

TEST(sim_modes, DirectPositionReportsTheMotorEffortItTakes) {
  ModesBot b;
  double peak = 0;
  run(b.sim, 200, [&](int) { b.act.set_command(b.direct, kPos, 0.4); },
      [&](int) { peak = std::max(peak, std::abs(b.act.joint_effort(b.direct))); });
  EXPECT_NEAR(peak, 2000.0, 1.0);  // accelerating 1 kg to 2 m/s within one 1 ms step
}

TEST(sim_modes, VelocityMotorReachesTheCommandThroughANegativeReduction) {
  ModesBot b;
  run(b.sim, 1000, [&](int) { b.act.set_command(b.wheel, kVel, 3.0); });
  EXPECT_NEAR(b.act.joint_velocity(b.wheel), -3.0, 1e-6);
  EXPECT_NEAR(b.act.velocity(b.wheel), 3.0, 1e-6);
  // The motor carries the URDF damping and friction: 0.01*3 + 0.01 = 0.04 N m, reported in actuator units.
  EXPECT_NEAR(b.act.effort(b.wheel), 0.04, 1e-3);
}

TEST(sim_modes, VelocityCommandsAreClampedToTheVelocityLimit) {
  ModesBot b;
  run(b.sim, 3000, [&](int) { b.act.set_command(b.wheel, kVel, 100.0); });
  EXPECT_NEAR(std::abs(b.act.joint_velocity(b.wheel)), 20.0, 1e-6);
}

TEST(sim_modes, VelocityPidReachesTheCommand) {
  ModesBot b;
  run(b.sim, 3000, [&](int) { b.act.set_command(b.vel_pid, kVel, 2.0); });
  // P only: steady state leaves the error that balances damping and friction (0.01*2+0.01 = 2*e).
  EXPECT_NEAR(b.act.joint_velocity(b.vel_pid), 2.0, 0.02);
}

TEST(sim_modes, EffortPassesThroughTheReductionAndIsClamped) {
  ModesBot b;
  b.act.set_command(b.effort, kEff, 1.0);
  b.sim.step();
  EXPECT_DOUBLE_EQ(b.act.joint_effort(b.effort), 2.0);
  EXPECT_DOUBLE_EQ(b.act.effort(b.effort), 1.0);
  b.act.set_command(b.effort, kEff, 100.0);
  b.sim.step();
  EXPECT_DOUBLE_EQ(b.act.joint_effort(b.effort), 10.0);  // URDF effort limit
}

TEST(sim_modes, LimitsHoldOnALinkWithoutCollisionGeometry) {
  ModesBot b;  // 'flap' has no <collision>: Bullet would skip its limit rows without the tiny collider
  double highest = 0;
  run(b.sim, 2000, [&](int) { b.act.set_command(b.effort, kEff, 5.0); },
      [&](int) { highest = std::max(highest, b.act.joint_position(b.effort)); });
  EXPECT_LT(highest, 0.5 + 1e-3);
  EXPECT_GT(highest, 0.49);
}

TEST(sim_modes, EStopZeroesVelocityAndEffortActuators) {
  ModesBot b;
  run(b.sim, 500, [&](int) { b.act.set_command(b.wheel, kVel, 3.0); });
  b.act.set_e_stop(true);
  run(b.sim, 500, [&](int) {
    b.act.set_command(b.wheel, kVel, 3.0);
    b.act.set_command(b.effort, kEff, 5.0);
  });
  EXPECT_NEAR(b.act.joint_velocity(b.wheel), 0.0, 1e-6);
  EXPECT_DOUBLE_EQ(b.act.joint_effort(b.effort), 0.0);
}

TEST(sim_simulation, PhysicsRunsSeveralStepsPerControlStep) {
  Simulation sim(turret(), {4000, 1000});
  EXPECT_EQ(sim.substeps(), 4);
  EXPECT_DOUBLE_EQ(sim.physics_dt(), 0.00025);
  run(sim, 5000, [&](int) { sim.actuators().set_command(1, kPos, 1.0); });
  EXPECT_EQ(sim.time_us(), 5000000);
  EXPECT_NEAR(sim.actuators().joint_position(1), 1.0, 0.01);
  EXPECT_THROW(Simulation(turret(), {1000, 300}), std::invalid_argument);
  EXPECT_THROW(Simulation(turret(), {1000, 0}), std::invalid_argument);
}

TEST(sim_simulation, IdenticalCommandsGiveBitIdenticalTrajectories) {
  Simulation a(turret(), {}), b(turret(), {});
  auto cmd = [](Simulation& s, int k) {
    s.actuators().set_command(0, kPos, 0.5 + 0.4 * std::sin(k * 0.003));
    s.actuators().set_command(1, kPos, 3.0 * std::sin(k * 0.001));
  };
  for (int k = 0; k < 5000; ++k) {
    cmd(a, k);
    cmd(b, k);
    a.step();
    b.step();
    for (int i = 0; i < 2; ++i) {
      ASSERT_EQ(a.actuators().position(i), b.actuators().position(i)) << k;
      ASSERT_EQ(a.actuators().velocity(i), b.actuators().velocity(i)) << k;
      ASSERT_EQ(a.actuators().effort(i), b.actuators().effort(i)) << k;
    }
  }
}

double micros_per_step(Simulation& sim, int steps, bool full) {
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < steps; ++k) {
    if (full)
      sim.step();
    else
      sim.multibody().step();
  }
  return std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count() / steps;
}

TEST(sim_timing, TurretStepCostsMicroseconds) {
  Simulation sim(turret(), {});
  for (int i = 0; i < 2; ++i) sim.actuators().set_command(i, kPos, 0.5);
  micros_per_step(sim, 1000, true);
  double full = 1e9, bare = 1e9;
  for (int round = 0; round < 3; ++round) {
    full = std::min(full, micros_per_step(sim, 5000, true));
    bare = std::min(bare, micros_per_step(sim, 5000, false));
  }
  std::printf("turret_bot: %.2f us per physics step with actuators, %.2f us bare stepSimulation\n", full, bare);
  EXPECT_LT(full, 200.0);  // ~5 us expected; generous for a loaded CI machine
}

// An N-link revolute chain, every joint with limits, damping and friction.
std::string chain_urdf(int n, double friction) {
  std::string s = "<?xml version=\"1.0\"?>\n<robot name=\"chain\">\n<link name=\"l0\"><inertial><mass value=\"1\"/>"
                  "<inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.01\" iyz=\"0\" izz=\"0.01\"/></inertial></link>\n";
  for (int i = 1; i <= n; ++i) {
    s += "<link name=\"l" + std::to_string(i) +
         "\"><inertial><origin xyz=\"0 0 0.05\"/><mass value=\"0.1\"/><inertia ixx=\"1e-4\" ixy=\"0\" ixz=\"0\" "
         "iyy=\"1e-4\" iyz=\"0\" izz=\"1e-4\"/></inertial></link>\n";
    s += "<joint name=\"j" + std::to_string(i) + "\" type=\"revolute\"><parent link=\"l" + std::to_string(i - 1) +
         "\"/><child link=\"l" + std::to_string(i) + "\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"" +
         (i % 2 ? "1 0 0" : "0 1 0") + "\"/><limit lower=\"-1\" upper=\"1\" effort=\"100\" velocity=\"10\"/>" +
         "<dynamics damping=\"0.001\" friction=\"" + std::to_string(friction) + "\"/></joint>\n";
    s += "<transmission name=\"t" + std::to_string(i) +
         "\"><type>transmission_interface/SimpleTransmission</type><joint name=\"j" + std::to_string(i) +
         "\"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint><actuator "
         "name=\"a" + std::to_string(i) + "\"><mechanicalReduction>1</mechanicalReduction></actuator></transmission>\n";
  }
  return s + "</robot>\n";
}

TEST(sim_timing, FrictionStaysCheapOnA100JointChain) {
  const std::string dir = lcm_control::testing::temp_dir("sim_chain");
  double cost[2] = {1e9, 1e9};
  std::vector<std::unique_ptr<Simulation>> sims;
  for (int f = 0; f < 2; ++f) {
    const std::string path = dir + "/chain" + std::to_string(f) + ".urdf";
    std::ofstream(path) << chain_urdf(100, f ? 0.001 : 0.0);
    sims.push_back(std::make_unique<Simulation>(load_robot_model(path, ""), SimulationRates{}));
    for (int i = 0; i < sims[f]->actuators().size(); ++i) sims[f]->actuators().set_command(i, kEff, 0.0);
    micros_per_step(*sims[f], 200, true);
  }
  // Rounds alternate between the two, so a busy machine slows both alike; the best round of each counts.
  for (int round = 0; round < 5; ++round)
    for (int f = 0; f < 2; ++f) cost[f] = std::min(cost[f], micros_per_step(*sims[f], 1000, true));
  std::printf("chain100: %.1f us per step without friction, %.1f us with friction 0.001 (ratio %.2f)\n", cost[0],
              cost[1], cost[1] / cost[0]);
  EXPECT_LT(cost[1], 2.0 * cost[0]);  // PyBullet-style friction motors cost ~20x here
}

}  // namespace
}  // namespace lcm_control::sim
