// Stiff gains on light links (issue 30, item 5): the implicit joint damper on
// its own against the exact backward-Euler figure, and the light upright arm of
// test/e2e/data/stiff_arm.urdf.xacro holding still and moving under franka_gazebo's
// gains, where an explicit D term chattered at the velocity limit every step:
// with the PID in the simulator (pid_gains), and in a controller that sends
// efforts with the damping they hold (hardware_command_t::damping).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim_server/simulation.hpp"
#include "test/sim_server/sim_test_support.hpp"
#include "description/load.hpp"

namespace lcm_control::sim {
namespace {

using namespace testing;

std::string stiff_arm(const std::string& ext) {
  return std::string(LCM_CONTROL_SOURCE_DIR) + "/test/e2e/data/stiff_arm." + ext;
}

TEST(sim_stiff, TheImplicitDamperGivesTheBackwardEulerVelocityWhereExplicitDampingWouldDiverge) {
  const RobotModel m = load_robot_model(stiff_arm("urdf.xacro"), "");
  Multibody mb(m, 1e-3);
  const MultibodyJoint& j1 = mb.joints()[mb.joint_index("joint1")];
  ImplicitJointDamper* damper = mb.add_damper(j1.link);
  mb.size_solver_buffers();
  // c*dt/I = 10 (explicit: v' = (1 - 10) v, growing 9x a step); implicit: v' = v / (1 + 10).
  const double c = 10 * j1.effective_inertia / mb.dt();
  damper->set(c, 0, -1e9, 1e9);
  mb.set_state(j1.link, 0, 1.0);
  double v = 1.0;
  for (int k = 0; k < 3; ++k) {
    mb.step();
    v /= 11;
    EXPECT_NEAR(mb.velocity(j1.link), v, 1e-3 * v) << "step " << k;
    EXPECT_NEAR(damper->applied_torque(mb.dt()), -c * mb.velocity(j1.link), 1e-3 * c * v) << "step " << k;
  }
  // Bounded: it may not apply more than it is allowed to.
  damper->set(c, 0, -0.01, 0.01);
  mb.set_state(j1.link, 0, 1.0);
  mb.step();
  EXPECT_NEAR(damper->applied_torque(mb.dt()), -0.01, 1e-9);
}

// With an explicit torque in the same step: the damper starts from the velocity the torque gives, however far past
// the joint's velocity limit that is (Bullet clamped every coordinate to the robot's largest velocity limit inside the
// step, so the damper saw a fraction of the torque and a stiff effort joint barely moved); the limit then applies.
TEST(sim_stiff, AnExplicitTorqueAndTheDamperTogetherGiveTheBackwardEulerVelocity) {
  const RobotModel m = load_robot_model(stiff_arm("urdf.xacro"), "");
  for (const double c : {30.0, 0.5}) {
    Multibody mb(m, 1e-3);
    const MultibodyJoint& j1 = mb.joints()[mb.joint_index("joint1")];
    ImplicitJointDamper* damper = mb.add_damper(j1.link);
    mb.size_solver_buffers();
    damper->set(c, 0, -100, 100);
    const double tau = 10, dt = mb.dt(), inertia = j1.effective_inertia;
    mb.add_torque(j1.link, tau);
    mb.step();
    // (I + c dt) v' = tau dt: 0.327 rad/s for c = 30; 9.6 for c = 0.5, over the 2.175 limit.
    const double v = tau * dt / (inertia + c * dt);
    EXPECT_NEAR(damper->applied_torque(dt), -c * v, 1e-3 * c * v) << c;
    EXPECT_NEAR(mb.velocity(j1.link), std::min(v, j1.urdf->velocity_limit), 1e-3 * v) << c;
  }
}

TEST(sim_stiff, LightUprightArmUnderStiffPidGainsHoldsStillAndFollows) {
  Simulation sim(load_robot_model(stiff_arm("urdf.xacro"), stiff_arm("yaml")), {});
  Actuators& act = sim.actuators();
  for (int i = 0; i < act.size(); ++i) {
    // The explicit D term would be far past its bound on every joint of this arm (d*dt/I = 0.7 .. 79).
    const MultibodyJoint& j = sim.multibody().joints()[sim.multibody().joint_index(act.joint(i))];
    EXPECT_GT(act.gains(i).d * sim.physics_dt() / j.effective_inertia, 0.5) << act.joint(i);
    EXPECT_TRUE(act.implicit_derivative(i)) << act.joint(i);
  }
  double worst = 0;
  // A step to 0.1 rad (rate-limited by the velocity limits), then 1 s of holding there.
  run(sim, 2000, [&](int) { for (int i = 0; i < act.size(); ++i) act.set_command(i, kPos, 0.1); },
      [&](int k) {
        if (k >= 1000)
          for (int i = 0; i < act.size(); ++i) worst = std::max(worst, std::abs(act.joint_velocity(i)));
      });
  EXPECT_LT(worst, 0.05);
  for (int i = 0; i < act.size(); ++i) EXPECT_NEAR(act.joint_position(i), 0.1, 0.01) << act.joint(i);
  // The reported effort includes the damper's share: at rest it is the gravity torque, not a chattering one.
  for (int i = 0; i < act.size(); ++i) EXPECT_LT(std::abs(act.joint_effort(i)), 2.0) << act.joint(i);
  // Tuned at run time to a soft D: back to the explicit term (stable there), still holding.
  PidGains soft = act.gains(1);
  soft.d = 0.1;
  ASSERT_TRUE(act.set_gains(1, soft));
  EXPECT_FALSE(act.implicit_derivative(1));
  worst = 0;
  run(sim, 1000, [&](int) { for (int i = 0; i < act.size(); ++i) act.set_command(i, kPos, 0.1); },
      [&](int k) {
        if (k >= 500) worst = std::max(worst, std::abs(act.joint_velocity(1)));
      });
  EXPECT_LT(worst, 0.05);
}

// The effort JointTrajectoryController's PID as the controller manager runs it: u = p*e - d*v from the state
// before the step, clamped to the effort limit, sent with `damping` d (or 0: the plain effort of before).
struct ControllerSidePid {
  std::vector<double> p, d;
  double goal = 0.1;
  void command(Actuators& act, bool with_damping, const RobotModel& m) const {
    for (int i = 0; i < act.size(); ++i) {
      const double limit = m.joint(act.joint(i))->effort_limit;
      const double u = std::clamp(p[i] * (goal - act.joint_position(i)) - d[i] * act.joint_velocity(i), -limit, limit);
      act.set_command(i, kEff, u, with_damping ? d[i] : 0.0);
    }
  }
};

TEST(sim_stiff, AnEffortCommandsDampingIsAppliedImplicitlyOnALightUprightArm) {
  LoadOptions o;
  o.xacro_args = {{"interface", "EffortJointInterface"}};
  const RobotModel m = load_robot_model(stiff_arm("urdf.xacro"), std::vector<std::string>{}, o);
  const ControllerSidePid pid{{600, 600, 250, 50}, {30, 30, 10, 5}};
  auto hold = [&](bool with_damping, double* worst_effort_excess) {
    Simulation sim(m, {});
    Actuators& act = sim.actuators();
    double worst = 0;
    run(sim, 2000, [&](int) { pid.command(act, with_damping, m); },
        [&](int k) {
          if (k < 1000) return;
          for (int i = 0; i < act.size(); ++i) {
            worst = std::max(worst, std::abs(act.joint_velocity(i)));
            const double limit = m.joint(act.joint(i))->effort_limit;
            if (worst_effort_excess)
              *worst_effort_excess = std::max(*worst_effort_excess, std::abs(act.joint_effort(i)) - limit);
          }
        });
    if (with_damping) {
      for (int i = 0; i < act.size(); ++i) {
        EXPECT_TRUE(act.implicit_derivative(i)) << act.joint(i);
        // p alone against gravity: the error is the gravity torque over p (franka_gazebo's gains have no I).
        EXPECT_NEAR(act.joint_position(i), 0.1, 0.01) << act.joint(i);
      }
    }
    return worst;
  };
  // The plain effort (an explicit D term) chatters at the velocity limits, as the upright Panda did.
  EXPECT_GT(hold(false, nullptr), 1.0);
  double excess = -1e9;
  EXPECT_LT(hold(true, &excess), 0.05);
  // The explicit part and the damper together stay within the effort limit.
  EXPECT_LE(excess, 1e-6);
}

// A light wheel's URDF damping far past what an explicit torque can take (c*dt/I = 8.9): simulated whole, in the
// solver, not lowered to I/dt. An effort u then spins it at u/c (lowered, it would be 8.9 times as fast), and a
// velocity PID through effort (the gz diffbot's p 0.1, i 1, feedforward 0.95) settles on its reference instead of
// swinging between the velocity limits.
TEST(sim_stiff, AStiffUrdfDampingOnAnActuatedJointIsAppliedWholeInTheSolver) {
  const RobotModel m = load_robot_model(data("light_wheel.urdf"), "");
  const double c = m.joint("wheel_joint")->damping;
  {
    Simulation sim(m, {});
    for (const std::string& w : sim.warnings()) EXPECT_EQ(w.find("too stiff"), std::string::npos) << w;
    Actuators& act = sim.actuators();
    run(sim, 500, [&](int) { act.set_command(0, kEff, 0.1, 0.0); });
    EXPECT_NEAR(act.joint_velocity(0), 0.1 / c, 0.01 * 0.1 / c);
  }
  Simulation sim(m, {});
  Actuators& act = sim.actuators();
  const double reference = 5.0;
  double integral = 0, worst_late = 0;
  run(
      sim, 3000,
      [&](int) {
        const double error = reference - act.joint_velocity(0);
        integral = std::clamp(integral + 1.0 * error * sim.control_period(), -20.0, 20.0);
        act.set_command(0, kEff, 0.95 * reference + 0.1 * error + integral, 0.0);
      },
      [&](int k) {
        if (k >= 2000) worst_late = std::max(worst_late, std::abs(act.joint_velocity(0) - reference));
      });
  std::printf("light wheel: %.4f rad/s for %.1f; in the last second at most %.2e off\n", act.joint_velocity(0),
              reference, worst_late);
  EXPECT_LT(worst_late, 0.01 * reference);
}

}  // namespace
}  // namespace lcm_control::sim
