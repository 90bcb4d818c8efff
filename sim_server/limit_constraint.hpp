// Joint position limits that a fast joint cannot cross: Bullet's own limit
// constraint acts only once the joint is past the limit, so a joint arriving at
// v overshoots by v*dt before it is pushed back. This one also acts when the
// joint would reach the limit within the step (a speculative row: approach
// speed capped at gap/dt), and pushes a joint that is past it back with the
// solver's ERP.
#pragma once

#include <BulletDynamics/Featherstone/btMultiBodyJointLimitConstraint.h>

namespace lcm_control::sim {

class SpeculativeJointLimit : public btMultiBodyJointLimitConstraint {
 public:
  SpeculativeJointLimit(btMultiBody* body, int link, double lower, double upper)
      : btMultiBodyJointLimitConstraint(body, link, lower, upper) {}

  void createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                            const btContactSolverInfo& info) override;
};

}  // namespace lcm_control::sim
