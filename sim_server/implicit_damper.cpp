#include "sim_server/implicit_damper.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>

namespace lcm_control::sim {

void ImplicitJointDamper::set(double damping, double target_velocity, double min_torque, double max_torque) {
  damping_ = damping > 0 ? damping : 0;
  target_ = target_velocity;
  min_torque_ = min_torque;
  max_torque_ = max_torque;
}

void ImplicitJointDamper::createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                                               const btContactSolverInfo& info) {
  if (m_numDofsFinalized != m_jacSizeBoth) finalizeMultiDof();
  const double dt = info.m_timeStep;
  // Always one row (a zero damping gives a row that applies nothing), so the solver's buffers, sized once with every
  // constraint in the world, never grow in a step.
  btMultiBodySolverConstraint& c = rows.expandNonInitializing();
  c.m_orgConstraint = this;
  c.m_orgDofIndex = 0;
  const btVector3 zero(0, 0, 0);
  const double rel_vel = fillMultiBodyConstraint(c, data, jacobianA(0), jacobianB(0), zero, zero, zero, zero, 0, info,
                                                 min_torque_ * dt, max_torque_ * dt, false, 1, false, target_);
  // Bullet's row is a hard velocity constraint: impulse p with (A + 0) p = target - v, A = J M^-1 J^T = 1 /
  // m_jacDiagABInv. The damper is the soft one, p = c*dt*(target - v_next) with v_next = v + A p, i.e.
  // (A + 1/(c dt)) p = target - v: the solver's CFM term (it iterates dp = rhs - p*cfm - J dv * jacDiagABInv).
  const double a = c.m_jacDiagABInv > 0 ? 1.0 / c.m_jacDiagABInv : 0.0;
  if (damping_ <= 0 || a <= 0) {
    c.m_jacDiagABInv = 0;
    c.m_rhs = 0;
    c.m_cfm = 0;
  } else {
    const double cfm = 1.0 / (damping_ * dt);
    c.m_jacDiagABInv = 1.0 / (a + cfm);
    c.m_rhs = (target_ - rel_vel) * c.m_jacDiagABInv;
    c.m_cfm = cfm * c.m_jacDiagABInv;
  }
  const btMultibodyLink& link = m_bodyA->getLink(m_linkA);
  const btQuaternion rot = link.m_cachedWorldTransform.getRotation();
  if (link.m_jointType == btMultibodyLink::eRevolute) {
    const btVector3 axis = quatRotate(rot, link.m_axes[0].m_topVec);
    c.m_contactNormal1.setZero();
    c.m_contactNormal2.setZero();
    c.m_relpos1CrossNormal = axis;
    c.m_relpos2CrossNormal = -axis;
  } else {
    const btVector3 axis = quatRotate(rot, link.m_axes[0].m_bottomVec);
    c.m_contactNormal1 = axis;
    c.m_contactNormal2 = -axis;
    c.m_relpos1CrossNormal.setZero();
    c.m_relpos2CrossNormal.setZero();
  }
}

}  // namespace lcm_control::sim
