#include "sim_server/limit_constraint.hpp"

#include <BulletDynamics/Featherstone/btMultiBody.h>

namespace lcm_control::sim {

void SpeculativeJointLimit::createConstraintRows(btMultiBodyConstraintArray& rows, btMultiBodyJacobianData& data,
                                                 const btContactSolverInfo& info) {
  if (m_numDofsFinalized != m_jacSizeBoth) finalizeMultiDof();
  const btMultibodyLink& link = m_bodyA->getLink(m_linkA);
  const double q = m_bodyA->getJointPos(m_linkA), qd = m_bodyA->getJointVel(m_linkA);
  const double dt = info.m_timeStep;
  // Row 0 keeps q above the lower bound (its Jacobian is +1), row 1 below the upper one (-1):
  // "gap" is the distance left, "away" the velocity leaving the bound.
  for (int row = 0; row < 2; ++row) {
    const double gap = row == 0 ? q - m_lowerBound : m_upperBound - q;
    const double away = row == 0 ? qd : -qd;
    // Margin 2x: other rows solved in the same pass may speed the joint up further.
    if (gap > 0 && gap + 2.0 * away * dt > 0) continue;
    const double target = gap >= 0 ? -gap / dt : -gap * info.m_erp / dt;
    btMultiBodySolverConstraint& c = rows.expandNonInitializing();
    c.m_orgConstraint = this;
    c.m_orgDofIndex = row;
    const btVector3 zero(0, 0, 0);
    fillMultiBodyConstraint(c, data, jacobianA(row), jacobianB(row), zero, zero, zero, zero, 0, info, 0,
                            m_maxAppliedImpulse, false, 1, false, target);
    const double dir = row == 0 ? 1.0 : -1.0;
    const btQuaternion rot = link.m_cachedWorldTransform.getRotation();
    if (link.m_jointType == btMultibodyLink::eRevolute) {
      const btVector3 axis = dir * quatRotate(rot, link.m_axes[0].m_topVec);
      c.m_contactNormal1.setZero();
      c.m_contactNormal2.setZero();
      c.m_relpos1CrossNormal = axis;
      c.m_relpos2CrossNormal = -axis;
    } else {
      const btVector3 axis = dir * quatRotate(rot, link.m_axes[0].m_bottomVec);
      c.m_contactNormal1 = axis;
      c.m_contactNormal2 = -axis;
      c.m_relpos1CrossNormal.setZero();
      c.m_relpos2CrossNormal.setZero();
    }
  }
}

}  // namespace lcm_control::sim
