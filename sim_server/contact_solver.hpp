// Bullet's multibody constraint solver as the simulation needs it: its buffers made roomy before a step fills them
// (so a step with more rows than ever before does not cost their square), and directional friction for the links
// that declare it (<gazebo reference="LINK"><fdir1> with <mu1>/<mu2>: a mecanum or omni wheel's rollers as
// Gazebo's ODE models them): mu1 along fdir1, mu2 across it, each bounded by the contact's normal impulse as it is
// solved, in place of Bullet's isotropic cone.
#pragma once

#ifndef BT_USE_DOUBLE_PRECISION
#error "sim_server needs Bullet in double precision: use pkg-config bullet-float64 (it defines BT_USE_DOUBLE_PRECISION)"
#endif

#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>

#include <vector>

namespace lcm_control::sim {

class ContactSolver final : public btMultiBodyConstraintSolver {
 public:
  // `collider` gets mu1 along `fdir1` and mu2 across it, fdir1 given in `frame`'s collider frame (the COM frame of
  // the link it is expressed in); each times the other body's friction, as Bullet combines coefficients. Sets the
  // collider's own friction to 0 so that Bullet's isotropic rows for its contacts apply nothing.
  void add_directional_friction(btCollisionObject* collider, const btCollisionObject* frame, const btVector3& fdir1,
                                double mu1, double mu2);

 protected:
  btScalar solveGroupCacheFriendlySetup(btCollisionObject** bodies, int num_bodies, btPersistentManifold** manifolds,
                                        int num_manifolds, btTypedConstraint** constraints, int num_constraints,
                                        const btContactSolverInfo& info, btIDebugDraw* draw) override;
  void convertContacts(btPersistentManifold** manifolds, int num_manifolds, const btContactSolverInfo& info) override;
  btScalar solveSingleIteration(int iteration, btCollisionObject** bodies, int num_bodies,
                                btPersistentManifold** manifolds, int num_manifolds, btTypedConstraint** constraints,
                                int num_constraints, const btContactSolverInfo& info, btIDebugDraw* draw) override;

 private:
  struct Directional {
    const btCollisionObject* frame;
    btVector3 fdir1;  // in the frame collider's frame
    double mu1, mu2;
  };
  std::vector<Directional> directional_;  // by the collider's user index 2
  // This step's rows along and across fdir1, each bounded by m_friction times its contact's normal impulse.
  btAlignedObjectArray<btMultiBodySolverConstraint> rows_;
};

}  // namespace lcm_control::sim
