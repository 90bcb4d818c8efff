#include "sim_server/multibody_builder.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "description/text.hpp"

namespace lcm_control::sim {

namespace {

constexpr double kGravity = 9.81;
constexpr double kMasslessLinkMass = 1e-3;   // kg, for moving links the URDF gives no mass
constexpr double kMasslessLinkInertia = 1e-6;
constexpr double kMaxCoordinateVelocity = 1e4;  // rad/s, m/s: Bullet's clamp on every coordinate, a safety net only
// Limits must stop a 1000 N actuator and the momentum of a fast heavy arm within one step; the cap is
// only a safety net against a runaway solve.
constexpr double kLimitMaxImpulse = 1e6;
// A mimic's gear corrects this fraction of its position error per step (on top of holding the velocities in ratio).
constexpr double kGearErp = 0.5;
constexpr double kTinyColliderRadius = 1e-3;
constexpr double kDefaultFriction = 1.0;  // Gazebo's mu1 default

struct LinkInertia {
  double mass = 0;
  Eigen::Vector3d principal = Eigen::Vector3d::Zero();
  Eigen::Isometry3d link_from_com = Eigen::Isometry3d::Identity();
};

// The URDF inertial as Bullet needs it: a diagonal tensor in a COM frame rotated onto the principal axes.
// followers_inertia: for a massless link whose joint other joints mimic (a car-like robot's virtual wheel), the
// moments those joints' links put on it through their gears (kg m^2; 0 for none).
LinkInertia principal_inertia(const Link& link, bool moving, const std::string& urdf,
                              std::vector<std::string>& warnings, double followers_inertia = 0) {
  LinkInertia out;
  if (link.inertial) out.link_from_com = link.inertial->origin;
  if (!link.inertial || link.inertial->mass <= 0) {
    if (moving) {
      // A 1 g link held to heavy followers by gears is a stiff, ill-conditioned solve (its actuator's speed came out
      // twice the command): it gets their moment of inertia, its mass staying negligible.
      const double inertia = std::max(kMasslessLinkInertia, followers_inertia);
      out.mass = kMasslessLinkMass;
      out.principal.setConstant(inertia);
      warnings.push_back(fmt::format("{}: link '{}' moves but has no mass; simulated with {} kg, inertia {:g} kg m^2{}",
                                     urdf, link.name, kMasslessLinkMass, inertia,
                                     followers_inertia > kMasslessLinkInertia ? " (its mimic joints' links')" : ""));
    }
    return out;
  }
  out.mass = link.inertial->mass;
  const Eigen::Matrix3d& I = link.inertial->inertia;
  const double scale = I.diagonal().cwiseAbs().maxCoeff();
  const bool diagonal = std::abs(I(0, 1)) <= 1e-12 * scale && std::abs(I(0, 2)) <= 1e-12 * scale &&
                        std::abs(I(1, 2)) <= 1e-12 * scale;
  if (diagonal) {
    out.principal = I.diagonal();
  } else {
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(I);
    Eigen::Matrix3d axes = es.eigenvectors();
    if (axes.determinant() < 0) axes.col(2) *= -1;
    out.principal = es.eigenvalues();
    out.link_from_com.linear() = out.link_from_com.linear() * axes;
  }
  const Eigen::Vector3d& p = out.principal;
  const double tol = 1e-9 * std::max(scale, 1e-12);
  if (p.minCoeff() < -tol || p.x() > p.y() + p.z() + tol || p.y() > p.x() + p.z() + tol ||
      p.z() > p.x() + p.y() + tol)
    warnings.push_back(fmt::format("{}: link '{}': inertia (principal moments {:g} {:g} {:g}) is not physical "
                                   "(a moment exceeds the sum of the other two); simulated as given",
                                   urdf, link.name, p.x(), p.y(), p.z()));
  out.principal = out.principal.cwiseMax(0.0);
  return out;
}

btVector3 bt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }

btQuaternion bt_rotation(const Eigen::Matrix3d& r) {
  btQuaternion q;
  to_bt(Eigen::Isometry3d(r)).getBasis().getRotation(q);
  return q;
}

}  // namespace

bool floating_base_for(const RobotModel& model, BaseMount mount) {
  if (mount != BaseMount::Auto) return mount == BaseMount::Floating;
  return model.root_link != "world";
}

Multibody::Multibody(const RobotModel& model, double dt, const InitialPositions& initial, const WorldOptions& world)
    : dt_(dt) {
  collision_config_ = std::make_unique<btDefaultCollisionConfiguration>();
  dispatcher_ = std::make_unique<btCollisionDispatcher>(collision_config_.get());
  broadphase_ = std::make_unique<btDbvtBroadphase>();
  solver_ = std::make_unique<ContactSolver>();
  world_ = std::make_unique<btMultiBodyDynamicsWorld>(dispatcher_.get(), broadphase_.get(), solver_.get(),
                                                      collision_config_.get());
  world_->setGravity(btVector3(0, 0, -kGravity));
  world_->getSolverInfo().m_numIterations = 50;
  build(model, world);
  set_initial_positions(model, initial);
  if (world.floating_base && world.ground) rest_on_ground(model);
  compute_effective_inertias();
}

void Multibody::rest_on_ground(const RobotModel& model) {
  double lowest = std::numeric_limits<double>::infinity();
  std::string lowest_link;
  for (const auto& [name, index] : link_index_) {
    const btMultiBodyLinkCollider* col = index < 0 ? body_->getBaseCollider() : body_->getLink(index).m_collider;
    if (!col || col->getBroadphaseHandle() == nullptr || col->getBroadphaseHandle()->m_collisionFilterGroup == 0)
      continue;  // the tiny collider of a geometry-less link touches nothing
    btVector3 lo, hi;
    col->getCollisionShape()->getAabb(col->getWorldTransform(), lo, hi);
    if (lo.z() < lowest) {
      lowest = lo.z();
      lowest_link = name;
    }
  }
  if (!(lowest < 0)) return;  // above the ground (it falls, as in Gazebo) or nothing collides
  btTransform base = body_->getBaseWorldTransform();
  base.getOrigin().setZ(base.getOrigin().z() - lowest);
  body_->setBaseWorldTransform(base);
  set_state_refresh();
  start_notes_.push_back(fmt::format("robot '{}': its lowest collision shape (link '{}') would start {:.4g} m inside "
                                     "the ground plane; the floating base starts lifted by {:.4g} m so it rests on "
                                     "the ground (start it higher with --base-pose / spawn_model -z to choose)",
                                     model.name, lowest_link, -lowest, -lowest));
}

void Multibody::step() {
  for (const auto& [link, f] : antigravity_) {
    if (link < 0)
      body_->addBaseForce(f);
    else
      body_->addLinkForce(link, f);
  }
  world_->stepSimulation(dt_, 0, dt_);
  for (const MultibodyJoint& j : joints_) {
    if (j.max_velocity <= 0) continue;
    const double v = body_->getJointVel(j.link);
    if (std::abs(v) > j.max_velocity) body_->setJointVel(j.link, std::copysign(j.max_velocity, v));
  }
}

void Multibody::set_initial_positions(const RobotModel& model, const InitialPositions& initial) {
  std::vector<std::string> moving;
  for (const MultibodyJoint& j : joints_) moving.push_back(j.urdf->name);
  for (const auto& [name, q] : initial) {
    if (joint_index(name) >= 0) {
      if (!std::isfinite(q))
        throw ModelError(fmt::format("initial position of joint '{}' is {}; give a finite number", name, q));
      continue;
    }
    const Joint* fixed = model.joint(name);
    if (fixed)
      throw ModelError(fmt::format("initial position of joint '{}': it is a {} joint in {}; only moving joints "
                                   "take one",
                                   name, to_string(fixed->type), model.urdf_path));
    const std::string near = closest_name(name, moving, 3);
    throw ModelError(fmt::format("initial position of joint '{}': {} has no joint of that name{}", name,
                                 model.urdf_path, near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near)));
  }
  for (const MultibodyJoint& j : joints_) {
    const auto it = initial.find(j.urdf->name);
    const double wanted = it == initial.end() ? 0.0 : it->second;
    double q = wanted;
    if (j.urdf->has_position_limits) q = std::clamp(wanted, j.urdf->lower, j.urdf->upper);
    if (q != wanted)
      start_warnings_.push_back(fmt::format("joint '{}' would start at {:g}{}, outside its limits [{:g}, {:g}] in {}; it "
                                      "starts at {:g} (choose a start with --initial-position {}=VALUE or the launch "
                                      "file's initial_positions)",
                                      j.urdf->name, wanted, it == initial.end() ? " (no initial position given)" : "",
                                      j.urdf->lower, j.urdf->upper, model.urdf_path, q, j.urdf->name));
    body_->setJointPos(j.link, q);
    body_->setJointVel(j.link, 0);
  }
  for (const MultibodyJoint& j : joints_) {  // a mimic starts where its joint puts it
    if (!j.urdf->mimic || j.leader_link < 0) continue;
    const double q = j.urdf->mimic->multiplier * body_->getJointPos(j.leader_link) + j.urdf->mimic->offset;
    const auto it = initial.find(j.urdf->name);
    if (it != initial.end() && it->second != q)
      start_warnings_.push_back(fmt::format("joint '{}' mimics '{}': it starts at {:g} (multiplier {:g}, offset {:g}), "
                                            "not the {:g} given; give '{}' its start instead",
                                            j.urdf->name, j.urdf->mimic->joint, q, j.urdf->mimic->multiplier,
                                            j.urdf->mimic->offset, it->second, j.urdf->mimic->joint));
    body_->setJointPos(j.link, q);
  }
  set_state_refresh();
}

Multibody::~Multibody() {
  if (ground_) world_->removeCollisionObject(ground_.get());
  for (auto& c : constraints_) world_->removeMultiBodyConstraint(c.get());
  for (auto& c : colliders_) world_->removeCollisionObject(c.get());
  if (body_) world_->removeMultiBody(body_.get());
}

void Multibody::build(const RobotModel& model, const WorldOptions& world) {
  const std::string& urdf = model.urdf_path;
  // Depth-first pre-order from the root, children in URDF order: a parent always precedes its children.
  std::vector<const Joint*> order;
  std::function<void(const std::string&)> visit = [&](const std::string& parent) {
    for (const Joint& j : model.joints)
      if (j.parent_link == parent) {
        order.push_back(&j);
        visit(j.child_link);
      }
  };
  visit(model.root_link);

  std::map<std::string, LinkInertia> inertia;
  std::map<std::string, bool> welded_to_base{{model.root_link, !world.floating_base}};  // welded to the world
  const Link* root = model.link(model.root_link);
  if (!root) throw ModelError(fmt::format("{}: root link '{}' not found", urdf, model.root_link));
  // A free base moves with the links welded to it; if none of them has mass, its root gets the massless moving
  // link's (a joint between it and the next link would otherwise move nothing and make Bullet's solve singular).
  double welded_mass = 0;
  std::function<void(const std::string&)> weigh = [&](const std::string& link) {
    const Link* l = model.link(link);
    if (l && l->inertial && l->inertial->mass > 0) welded_mass += l->inertial->mass;
    for (const Joint& j : model.joints)
      if (j.parent_link == link && j.type == JointType::Fixed) weigh(j.child_link);
  };
  if (world.floating_base) weigh(model.root_link);
  inertia[root->name] = principal_inertia(*root, world.floating_base && !(welded_mass > 0), urdf, warnings_);
  std::map<std::string, double> followers_inertia;  // a mimicked joint -> the moments its mimic joints' links add
  for (const Joint& j : model.joints) {
    const Link* l = model.link(j.child_link);
    if (!j.mimic || !l || !l->inertial) continue;
    const double m = j.mimic->multiplier;
    followers_inertia[j.mimic->joint] += l->inertial->inertia.diagonal().maxCoeff() * m * m;
  }
  for (const Joint* j : order) {
    const bool moving = j->type != JointType::Fixed;
    const auto f = followers_inertia.find(j->name);
    inertia[j->child_link] = principal_inertia(*model.link(j->child_link), moving, urdf, warnings_,
                                               f == followers_inertia.end() ? 0.0 : f->second);
    welded_to_base[j->child_link] = !moving && welded_to_base[j->parent_link];
  }

  const LinkInertia& base = inertia[root->name];
  body_ = std::make_unique<btMultiBody>(int(order.size()), base.mass, bt(base.principal),
                                        /*fixedBase=*/!world.floating_base, /*canSleep=*/false);
  const Eigen::Isometry3d world_from_root =
      Eigen::Translation3d(world.base_position) * Eigen::AngleAxisd(world.base_yaw, Eigen::Vector3d::UnitZ());
  body_->setBaseWorldTransform(to_bt(world_from_root * base.link_from_com));
  link_index_[root->name] = -1;
  model_root_ = root->name;
  link_from_com_[root->name] = base.link_from_com;

  for (int i = 0; i < int(order.size()); ++i) {
    const Joint& j = *order[i];
    const LinkInertia& child = inertia[j.child_link];
    link_index_[j.child_link] = i;
    link_from_com_[j.child_link] = child.link_from_com;
    const int parent = link_index_.at(j.parent_link);
    const Eigen::Isometry3d in_a = link_from_com_.at(j.parent_link).inverse() * j.origin;  // joint frame in parent COM
    const Eigen::Isometry3d in_b = child.link_from_com.inverse();                         // child frame in child COM
    const btQuaternion rot_parent_to_this = bt_rotation(in_b.linear() * in_a.linear().transpose());
    const btVector3 parent_com_to_pivot = bt(in_a.translation());
    const btVector3 pivot_to_com = bt(Eigen::Vector3d(-in_b.translation()));
    const btVector3 axis = bt(Eigen::Vector3d(in_b.linear() * j.axis));
    switch (j.type) {
      case JointType::Revolute:
      case JointType::Continuous:
        body_->setupRevolute(i, child.mass, bt(child.principal), parent, rot_parent_to_this, axis,
                             parent_com_to_pivot, pivot_to_com, true);
        break;
      case JointType::Prismatic:
        body_->setupPrismatic(i, child.mass, bt(child.principal), parent, rot_parent_to_this, axis,
                              parent_com_to_pivot, pivot_to_com, true);
        break;
      case JointType::Fixed:
        body_->setupFixed(i, child.mass, bt(child.principal), parent, rot_parent_to_this, parent_com_to_pivot,
                          pivot_to_com);
        break;
      default:
        throw ModelError(fmt::format("{}: joint '{}' is {}; only revolute, continuous, prismatic and fixed joints "
                                     "are supported",
                                     urdf, j.name, to_string(j.type)));
    }
    if (j.type != JointType::Fixed) {
      MultibodyJoint mj;
      mj.urdf = &j;
      mj.link = i;
      if (std::isfinite(j.velocity_limit) && j.velocity_limit > 0) mj.max_velocity = j.velocity_limit;
      joints_.push_back(mj);
    }
  }

  body_->finalizeMultiDof();
  body_->setLinearDamping(0);
  body_->setAngularDamping(0);
  body_->setCanSleep(false);
  body_->setHasSelfCollision(model.self_collide);  // as Gazebo: links of one model collide only with <self_collide>
  // Bullet clamps every coordinate to this inside the step, also the velocity after the explicit torques that the
  // solver's implicit rows (dampers, motors) start from: a URDF velocity limit here would let a light joint's
  // implicit D term see a fraction of the torque. The limits are applied per joint after the step (step()).
  body_->setMaxCoordinateVelocity(kMaxCoordinateVelocity);
  world_->addMultiBody(body_.get());

  // Colliders on every link: a link without one has island tag -1 and Bullet silently skips its limit
  // and motor rows, so geometry-less links get a tiny sphere that collides with nothing.
  shapes_.push_back(std::make_unique<btSphereShape>(kTinyColliderRadius));
  btCollisionShape* tiny = shapes_.back().get();
  auto add_collider = [&](const Link& link, int index) {
    btCollisionShape* shape = make_link_shape(link, link_from_com_.at(link.name).inverse(), shapes_, urdf);
    auto col = std::make_unique<btMultiBodyLinkCollider>(body_.get(), index);
    col->setCollisionShape(shape ? shape : tiny);
    col->setFriction(link.friction.value_or(kDefaultFriction));  // Bullet multiplies the two bodies' coefficients
    col->setRollingFriction(0);
    col->setSpinningFriction(0);
    int group = btBroadphaseProxy::DefaultFilter, mask = btBroadphaseProxy::AllFilter;
    if (welded_to_base.at(link.name)) {
      col->setCollisionFlags(col->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
      group = btBroadphaseProxy::StaticFilter;
      mask = btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter;
    }
    if (!shape) group = mask = 0;
    world_->addCollisionObject(col.get(), group, mask);
    if (index < 0)
      body_->setBaseCollider(col.get());
    else
      body_->getLink(index).m_collider = col.get();
    colliders_.push_back(std::move(col));
  };
  for (const auto& [name, index] : link_index_) {
    const Link* l = model.link(name);
    if (!l || !l->gravity_off) continue;
    const double mass = index < 0 ? body_->getBaseMass() : body_->getLinkMass(index);
    antigravity_.emplace_back(index, btVector3(0, 0, kGravity * mass));  // applied at the COM: no torque
  }
  add_collider(*root, -1);
  for (int i = 0; i < int(order.size()); ++i) add_collider(*model.link(order[i]->child_link), i);
  for (const auto& [name, index] : link_index_) {  // every link has a collider now: the frames fdir1 is given in
    const Link* l = model.link(name);
    if (!l || !l->friction_direction) continue;
    const Link::FrictionDirection& d = *l->friction_direction;
    const std::string& frame = d.frame.empty() ? name : d.frame;
    const int frame_index = link_index_.at(frame);
    const btCollisionObject* frame_collider =
        frame_index < 0 ? body_->getBaseCollider() : body_->getLink(frame_index).m_collider;
    const Eigen::Vector3d in_frame_com = link_from_com_.at(frame).linear().transpose() * d.fdir1;
    btCollisionObject* collider = index < 0 ? body_->getBaseCollider() : body_->getLink(index).m_collider;
    solver_->add_directional_friction(collider, frame_collider, bt(in_frame_com), l->friction.value_or(kDefaultFriction),
                                      d.mu2);
  }
  if (world.ground) {
    shapes_.push_back(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0));
    ground_ = std::make_unique<btCollisionObject>();
    ground_->setCollisionShape(shapes_.back().get());
    ground_->setFriction(1.0);  // times the link's: the link's coefficient is the contact's
    ground_->setCollisionFlags(ground_->getCollisionFlags() | btCollisionObject::CF_STATIC_OBJECT);
    world_->addCollisionObject(ground_.get(), btBroadphaseProxy::StaticFilter,
                               btBroadphaseProxy::AllFilter ^ btBroadphaseProxy::StaticFilter);
  }

  for (MultibodyJoint& mj : joints_) {
    if (!mj.urdf->has_position_limits) continue;
    auto limit = std::make_unique<SpeculativeJointLimit>(body_.get(), mj.link, mj.urdf->lower, mj.urdf->upper);
    limit->setMaxAppliedImpulse(kLimitMaxImpulse);
    world_->addMultiBodyConstraint(limit.get());
    mj.limit = limit.get();
    constraints_.push_back(std::move(limit));
  }

  // Mimic: q = multiplier * q_leader + offset, i.e. the gear row q + ratio * q_leader = target.
  for (MultibodyJoint& mj : joints_) {
    if (!mj.urdf->mimic) continue;
    const int leader = joint_index(mj.urdf->mimic->joint);
    if (leader < 0) continue;  // validated: a moving joint
    mj.leader_link = joints_[leader].link;
    auto gear = std::make_unique<btMultiBodyGearConstraint>(body_.get(), mj.link, body_.get(), mj.leader_link,
                                                            btVector3(0, 0, 0), btVector3(0, 0, 0),
                                                            btMatrix3x3::getIdentity(), btMatrix3x3::getIdentity());
    gear->setGearRatio(-mj.urdf->mimic->multiplier);
    gear->setRelativePositionTarget(mj.urdf->mimic->offset);
    gear->setErp(kGearErp);
    gear->setMaxAppliedImpulse(kLimitMaxImpulse);
    gear->finalizeMultiDof();
    world_->addMultiBodyConstraint(gear.get());
    mj.gear = gear.get();
    constraints_.push_back(std::move(gear));
  }

  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  body_->forwardKinematics(world_to_local, local_origin);
  body_->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
}

Eigen::Isometry3d Multibody::base_pose() const { return link_pose(model_root_); }

Eigen::Vector3d Multibody::base_linear_velocity() const {
  const btVector3 v = body_->getBaseVel();
  return {v.x(), v.y(), v.z()};
}

Eigen::Vector3d Multibody::base_angular_velocity() const {
  const btVector3 w = body_->getBaseOmega();
  return {w.x(), w.y(), w.z()};
}

double Multibody::mimic_effort(int k) const {
  const MultibodyJoint& j = joints_[k];
  return j.gear ? j.gear->getAppliedImpulse(0) / dt_ : 0.0;
}

void Multibody::compute_effective_inertias() {
  // Run the articulated-body pass once without advancing time, then read (M^-1)_jj per joint.
  btAlignedObjectArray<btScalar> scratch_r;
  btAlignedObjectArray<btVector3> scratch_v;
  btAlignedObjectArray<btMatrix3x3> scratch_m;
  body_->clearForcesAndTorques();
  body_->computeAccelerationsArticulatedBodyAlgorithmMultiDof(0, scratch_r, scratch_v, scratch_m, false, false, false);
  const int n = 6 + body_->getNumDofs();
  std::vector<btScalar> force(n, 0), response(n, 0);
  for (MultibodyJoint& mj : joints_) {
    const int dof = 6 + body_->getLink(mj.link).m_dofOffset;
    force[dof] = 1;
    body_->calcAccelerationDeltasMultiDof(force.data(), response.data(), scratch_r, scratch_v);
    force[dof] = 0;
    mj.effective_inertia = response[dof] > 0 ? 1.0 / response[dof] : 0;
  }
  body_->clearForcesAndTorques();
}

void Multibody::size_solver_buffers() {
  std::vector<std::pair<double, double>> state;
  for (const MultibodyJoint& j : joints_) {
    state.emplace_back(position(j.link), velocity(j.link));
    if (j.limit) {
      j.limit->setLowerBound(state.back().first);  // a zero gap on both sides: both rows active
      j.limit->setUpperBound(state.back().first);
    }
  }
  const btTransform base = body_->getBaseWorldTransform();  // a floating base moves in that step too
  const btVector3 base_vel = body_->getBaseVel(), base_omega = body_->getBaseOmega();
  step();
  body_->setBaseWorldTransform(base);
  body_->setBaseVel(base_vel);
  body_->setBaseOmega(base_omega);
  for (size_t k = 0; k < joints_.size(); ++k) {
    const MultibodyJoint& j = joints_[k];
    if (j.limit) {
      j.limit->setLowerBound(j.urdf->lower);
      j.limit->setUpperBound(j.urdf->upper);
    }
    body_->setJointPos(j.link, state[k].first);
    body_->setJointVel(j.link, state[k].second);
  }
  body_->clearForcesAndTorques();
  set_state_refresh();
}

void Multibody::add_link_wrench(int link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque) {
  const btVector3 f(force.x(), force.y(), force.z()), t(torque.x(), torque.y(), torque.z());
  if (link < 0) {
    body_->addBaseForce(f);
    body_->addBaseTorque(t);
  } else {
    body_->addLinkForce(link, f);
    body_->addLinkTorque(link, t);
  }
}

int Multibody::joint_index(const std::string& name) const {
  for (int k = 0; k < int(joints_.size()); ++k)
    if (joints_[k].urdf->name == name) return k;
  return -1;
}

void Multibody::set_state(int link, double q, double qd) {
  body_->setJointPos(link, q);
  body_->setJointVel(link, qd);
  set_state_refresh();
}

void Multibody::set_state_refresh() {
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
  body_->forwardKinematics(world_to_local, local_origin);
  body_->updateCollisionObjectWorldTransforms(world_to_local, local_origin);
}

btMultiBodyJointMotor* Multibody::add_motor(int link, double max_impulse) {
  auto motor = std::make_unique<btMultiBodyJointMotor>(body_.get(), link, 0, 0, max_impulse);
  motor->finalizeMultiDof();  // allocates the applied-impulse slot read before the first solve
  world_->addMultiBodyConstraint(motor.get());
  auto* raw = motor.get();
  constraints_.push_back(std::move(motor));
  return raw;
}

ImplicitJointDamper* Multibody::add_damper(int link) {
  auto damper = std::make_unique<ImplicitJointDamper>(body_.get(), link);
  damper->finalizeMultiDof();
  world_->addMultiBodyConstraint(damper.get());
  auto* raw = damper.get();
  constraints_.push_back(std::move(damper));
  return raw;
}

Eigen::Isometry3d Multibody::link_pose(const std::string& link) const {
  const int i = link_index_.at(link);
  btTransform world_from_com;
  if (i < 0) {
    world_from_com = body_->getBaseWorldTransform();
  } else {
    // Walk the cached parent-to-link rotations and offsets (valid after every step and set_state).
    world_from_com.setOrigin(body_->localPosToWorld(i, btVector3(0, 0, 0)));
    world_from_com.setBasis(body_->localFrameToWorld(i, btMatrix3x3::getIdentity()));
  }
  return from_bt(world_from_com) * link_from_com_.at(link).inverse();
}

Eigen::Vector3d Multibody::com_position(const std::string& link) const {
  return link_pose(link) * link_from_com_.at(link).translation();
}

}  // namespace lcm_control::sim
