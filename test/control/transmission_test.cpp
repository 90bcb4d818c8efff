#include "control/transmission.hpp"

#include <gtest/gtest.h>

using lcm_control::SimpleTransmission;

class SimpleTransmissionRoundTrip : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(SimpleTransmissionRoundTrip, JointActuatorJoint) {
  const auto [n, off] = GetParam();
  const SimpleTransmission t{n, off};
  for (double x : {-2.0, -0.3, 0.0, 0.7, 3.14}) {
    EXPECT_NEAR(t.actuator_to_joint_position(t.joint_to_actuator_position(x)), x, 1e-12);
    EXPECT_NEAR(t.actuator_to_joint_velocity(t.joint_to_actuator_velocity(x)), x, 1e-12);
    EXPECT_NEAR(t.actuator_to_joint_effort(t.joint_to_actuator_effort(x)), x, 1e-12);
  }
}

TEST_P(SimpleTransmissionRoundTrip, MatchesTransmissionInterfaceFormulas) {
  const auto [n, off] = GetParam();
  const SimpleTransmission t{n, off};
  // transmission_interface: xj = xa/n + off, vj = va/n, tau_j = n*tau_a.
  EXPECT_DOUBLE_EQ(t.actuator_to_joint_position(2.0), 2.0 / n + off);
  EXPECT_DOUBLE_EQ(t.actuator_to_joint_velocity(2.0), 2.0 / n);
  EXPECT_DOUBLE_EQ(t.actuator_to_joint_effort(2.0), 2.0 * n);
  EXPECT_DOUBLE_EQ(t.joint_to_actuator_position(1.0), n * (1.0 - off));
  EXPECT_DOUBLE_EQ(t.joint_to_actuator_velocity(1.0), n * 1.0);
  EXPECT_DOUBLE_EQ(t.joint_to_actuator_effort(1.0), 1.0 / n);
}

TEST_P(SimpleTransmissionRoundTrip, ADampingMapsAsEffortPerVelocity) {
  const auto [n, off] = GetParam();
  const SimpleTransmission t{n, off};
  // -d_a * v_a on the actuator is -d_j * v_j on the joint: tau_j = n * tau_a, v_a = n * v_j.
  const double d_j = 30.0, v_j = 0.7;
  const double d_a = t.joint_to_actuator_damping(d_j);
  EXPECT_NEAR(t.actuator_to_joint_effort(-d_a * t.joint_to_actuator_velocity(v_j)), -d_j * v_j, 1e-12);
  EXPECT_NEAR(t.actuator_to_joint_damping(d_a), d_j, 1e-12);
  EXPECT_GT(d_a, 0.0);  // a negative reduction flips both effort and velocity
}

INSTANTIATE_TEST_SUITE_P(Reductions, SimpleTransmissionRoundTrip,
                         ::testing::Values(std::pair{1.0, 0.0}, std::pair{2.5, 0.0}, std::pair{-3.0, 0.0},
                                           std::pair{1.0, 0.25}, std::pair{2.5, -0.5}, std::pair{-3.0, 1.2}));

TEST(SimpleTransmission, ReductionTwoHalvesTheJointMotion) {
  const SimpleTransmission t{2.0, 0.0};
  EXPECT_DOUBLE_EQ(t.actuator_to_joint_position(2.0), 1.0);
  EXPECT_DOUBLE_EQ(t.actuator_to_joint_effort(10.0), 20.0);
}

TEST(SimpleTransmission, NegativeReductionFlipsDirection) {
  const SimpleTransmission t{-3.0, 0.0};
  EXPECT_DOUBLE_EQ(t.actuator_to_joint_position(3.0), -1.0);
  EXPECT_DOUBLE_EQ(t.joint_to_actuator_velocity(1.0), -3.0);
}
