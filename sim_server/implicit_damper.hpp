// A joint damper that the constraint solver treats implicitly: the torque
// -c*(v_next - v_target) is computed from the velocity at the END of the step,
// solved together with limits, motors and the rest of the articulated body.
// An explicit torque -c*v is unstable once c*dt/I passes 2 (I: the inertia the
// joint moves, which for near-coaxial joints of light links is far below any
// one link's); this one is stable for every c >= 0, and for small c*dt/I it is
// the explicit torque to first order. One solver row (a soft velocity
// constraint, CFM = 1/(c*dt)), whose impulse is bounded so that it and an
// explicit torque applied alongside stay within the effort limit.
#pragma once

#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>

namespace lcm_control::sim {

class ImplicitJointDamper : public btMultiBodyJointMotor {
 public:
  ImplicitJointDamper(btMultiBody* body, int link) : btMultiBodyJointMotor(body, link, 0, 0) {}

  // c in N*m*s/rad (N*s/m), >= 0; the velocity it damps towards; the torque it may add, as [lower, upper] (N*m),
  // so that an explicit torque e applied in the same step stays within +-limit: [-limit - e, limit - e].
  // Real-time safe.
  void set(double damping, double target_velocity, double min_torque, double max_torque);
  // The torque (N*m or N) it applied in the last step.
  double applied_torque(double dt) { return getAppliedImpulse(0) / dt; }

  void createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                            const btContactSolverInfo& info) override;

 private:
  double damping_ = 0, target_ = 0, min_torque_ = 0, max_torque_ = 0;
};

}  // namespace lcm_control::sim
