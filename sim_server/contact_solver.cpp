#include "sim_server/contact_solver.hpp"

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace lcm_control::sim {

namespace {
constexpr double kMaxCombinedFriction = 10;  // Bullet's cap on a combined coefficient
}  // namespace

void ContactSolver::add_directional_friction(btCollisionObject* collider, const btCollisionObject* frame,
                                             const btVector3& fdir1, double mu1, double mu2) {
  collider->setUserIndex2(int(directional_.size()));
  collider->setFriction(0);
  directional_.push_back(Directional{frame, fdir1.normalized(), mu1, mu2});
}

// Bullet grows its Jacobian buffers to the exact size one row at a time (a copy of every row before for each new
// one), which took a 500-link chain 27 s to size and made a step with more active rows than ever before cost the
// square of their number. Here they grow once, to an upper bound of the step's rows (and only when that is more than
// ever before).
btScalar ContactSolver::solveGroupCacheFriendlySetup(btCollisionObject** bodies, int num_bodies,
                                                     btPersistentManifold** manifolds, int num_manifolds,
                                                     btTypedConstraint** constraints, int num_constraints,
                                                     const btContactSolverInfo& info, btIDebugDraw* draw) {
  int64_t values = 0, dofs = 6;
  for (int i = 0; i < m_tmpNumMultiBodyConstraints; ++i) {
    btMultiBodyConstraint* c = m_tmpMultiBodyConstraints[i];
    const int64_t n = (c->getMultiBodyA() ? c->getMultiBodyA()->getNumDofs() + 6 : 0) +
                      (c->getMultiBodyB() ? c->getMultiBodyB()->getNumDofs() + 6 : 0);
    values += int64_t(c->getNumRows()) * n;
    dofs = std::max(dofs, n);
  }
  // A contact point: its normal, two friction and two torsional rows, and two directional ones.
  for (int m = 0; m < num_manifolds; ++m) values += int64_t(manifolds[m]->getNumContacts()) * 7 * 2 * dofs;
  if (values > m_data.m_jacobians.capacity() && values < INT32_MAX) {
    m_data.m_jacobians.reserve(int(values));
    m_data.m_deltaVelocitiesUnitImpulse.reserve(int(values));
  }
  rows_.resize(0);
  return btMultiBodyConstraintSolver::solveGroupCacheFriendlySetup(bodies, num_bodies, manifolds, num_manifolds,
                                                                   constraints, num_constraints, info, draw);
}

void ContactSolver::convertContacts(btPersistentManifold** manifolds, int num_manifolds,
                                    const btContactSolverInfo& info) {
  btMultiBodyConstraintSolver::convertContacts(manifolds, num_manifolds, info);
  if (directional_.empty()) return;
  // Bullet made one normal row per contact point within the processing threshold, manifold by manifold in order;
  // `k` walks those rows alongside.
  int k = 0;
  const int normals = m_multiBodyNormalContactConstraints.size();
  for (int m = 0; m < num_manifolds; ++m) {
    btPersistentManifold* manifold = manifolds[m];
    auto* a = const_cast<btCollisionObject*>(manifold->getBody0());
    auto* b = const_cast<btCollisionObject*>(manifold->getBody1());
    const bool a_directional = a->getUserIndex2() >= 0 && a->getUserIndex2() < int(directional_.size());
    const bool b_directional = b->getUserIndex2() >= 0 && b->getUserIndex2() < int(directional_.size());
    if (!a_directional && !b_directional) continue;
    const Directional& d = directional_[size_t(a_directional ? a->getUserIndex2() : b->getUserIndex2())];
    const btCollisionObject* other = a_directional ? b : a;
    const double other_friction = other->getFriction();
    const btVector3 fdir = d.frame->getWorldTransform().getBasis() * d.fdir1;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      btManifoldPoint& cp = manifold->getContactPoint(p);
      if (cp.getDistance() > manifold->getContactProcessingThreshold()) continue;
      while (k < normals && m_multiBodyNormalContactConstraints[k].m_originalContactPoint != &cp) ++k;
      if (k == normals) return;  // not a multibody contact: Bullet made no row of ours for it
      const btVector3& n = cp.m_normalWorldOnB;
      btVector3 along = fdir - n * fdir.dot(n);
      if (along.length2() < 1e-12) {  // fdir1 along the normal: no direction in the contact plane to prefer
        btVector3 u, v;
        btPlaneSpace1(n, u, v);
        along = u;
      }
      along.normalize();
      const btVector3 across = n.cross(along);
      const double mu[2] = {std::min(d.mu1 * other_friction, kMaxCombinedFriction),
                            std::min(d.mu2 * other_friction, kMaxCombinedFriction)};
      const btVector3 dirs[2] = {along, across};
      for (int r = 0; r < 2; ++r) {
        if (mu[r] <= 0) continue;
        addMultiBodyFrictionConstraint(dirs[r], 0, manifold, k, cp, a, b, info.m_sor, info);
        // Ours, out of Bullet's friction rows (which it solves in pairs against a round cone).
        rows_.push_back(m_multiBodyFrictionContactConstraints[m_multiBodyFrictionContactConstraints.size() - 1]);
        m_multiBodyFrictionContactConstraints.pop_back();
        rows_[rows_.size() - 1].m_friction = mu[r];
      }
      ++k;
    }
  }
}

btScalar ContactSolver::solveSingleIteration(int iteration, btCollisionObject** bodies, int num_bodies,
                                             btPersistentManifold** manifolds, int num_manifolds,
                                             btTypedConstraint** constraints, int num_constraints,
                                             const btContactSolverInfo& info, btIDebugDraw* draw) {
  btScalar residual = btMultiBodyConstraintSolver::solveSingleIteration(
      iteration, bodies, num_bodies, manifolds, num_manifolds, constraints, num_constraints, info, draw);
  if (iteration >= info.m_numIterations) return residual;
  for (int i = 0; i < rows_.size(); ++i) {
    btMultiBodySolverConstraint& row = rows_[i];
    const btScalar normal = m_multiBodyNormalContactConstraints[row.m_frictionIndex].m_appliedImpulse;
    row.m_lowerLimit = -row.m_friction * normal;
    row.m_upperLimit = row.m_friction * normal;
    const btScalar r = resolveSingleConstraintRowGeneric(row);
    residual = std::max(residual, r * r);
    if (row.m_multiBodyA) row.m_multiBodyA->setPosUpdated(false);
    if (row.m_multiBodyB) row.m_multiBodyB->setPosUpdated(false);
  }
  return residual;
}

}  // namespace lcm_control::sim
