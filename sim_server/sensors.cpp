#include "sim_server/sensors.hpp"

#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>

#include <cmath>

namespace lcm_control::sim {

namespace {

Eigen::Vector3d eig(const btVector3& v) { return {v.x(), v.y(), v.z()}; }

// A manifold point this close (or with an impulse) is a contact [m].
constexpr double kContactSlop = 1e-4;

}  // namespace

SensorBank::SensorBank(const RobotModel& model, Multibody& multibody, uint64_t seed)
    : mb_(multibody), dt_(multibody.dt()), rng_(seed) {
  btMultiBody& body = mb_.body();
  const int n = body.getNumLinks() + 1;
  gravity_ = eig(mb_.world().getGravity());
  link_mass_.assign(n, 0);
  link_inertia_.assign(n, Eigen::Vector3d::Zero());
  gravity_off_.assign(n, 0);
  link_mass_[0] = body.getBaseMass();
  link_inertia_[0] = eig(body.getBaseInertia());
  for (int i = 0; i + 1 < n; ++i) {
    link_mass_[i + 1] = body.getLinkMass(i);
    link_inertia_[i + 1] = eig(body.getLinkInertia(i));
  }
  for (const Link& l : model.links)
    if (l.gravity_off) gravity_off_[mb_.link_index(l.name) + 1] = 1;

  for (const SensorSpec& spec : model.sensors) {
    if (!spec.simulated()) continue;
    const int slot = mb_.link_index(spec.link) + 1;
    const Eigen::Isometry3d com_from_link = mb_.link_from_com(spec.link).inverse();
    Sensor s{spec.kind, 0, values_.size(), {}, {}};
    switch (spec.kind) {
      case SensorKind::Imu:
        s.index = int(imus_.size());
        imus_.push_back({slot, com_from_link * spec.pose, Eigen::Vector3d::Zero()});
        s.noise = {{}, {}, {}, {}};  // orientation
        s.noise.insert(s.noise.end(), spec.angular_velocity.begin(), spec.angular_velocity.end());
        s.noise.insert(s.noise.end(), spec.linear_acceleration.begin(), spec.linear_acceleration.end());
        need_links_ = true;
        break;
      case SensorKind::ForceTorque: {
        const Joint* joint = model.joint(spec.joint);
        ForceTorque ft;
        ft.child = slot;
        ft.parent = mb_.link_index(joint->parent_link) + 1;
        ft.com_from_joint = com_from_link;
        ft.parent_com_from_link = mb_.link_from_com(joint->parent_link).inverse().linear();
        ft.joint_from_sensor = spec.pose;
        ft.frame = spec.frame;
        ft.sign = spec.direction == MeasureDirection::ParentToChild ? 1.0 : -1.0;
        for (int k = 1; k < n; ++k) {  // a parent precedes its children in Bullet's order
          int up = k;
          while (up > 0 && up != slot) up = body.getParent(up - 1) + 1;
          if (up == slot) ft.subtree.push_back(k);
        }
        s.index = int(fts_.size());
        fts_.push_back(std::move(ft));
        s.noise.insert(s.noise.end(), spec.force.begin(), spec.force.end());
        s.noise.insert(s.noise.end(), spec.torque.begin(), spec.torque.end());
        need_links_ = need_contacts_ = true;
        break;
      }
      case SensorKind::Contact:
        s.index = int(contacts_.size());
        contacts_.push_back({slot});
        s.noise.resize(2);
        need_contacts_ = true;
        break;
      case SensorKind::Other: continue;
    }
    for (const std::string& i : sensor_interfaces(spec.kind)) names_.push_back(spec.name + "/" + i);
    values_.resize(names_.size(), 0.0);
    s.bias.resize(s.noise.size(), 0.0);
    for (size_t k = 0; k < s.noise.size(); ++k) {
      const GaussianNoise& g = s.noise[k];
      if (g.bias_mean == 0 && g.bias_stddev == 0) continue;
      const double b = g.bias_mean + g.bias_stddev * normal_(rng_);
      s.bias[k] = std::uniform_int_distribution<int>(0, 1)(rng_) ? b : -b;  // SDF: a bias of random sign
    }
    sensors_.push_back(std::move(s));
  }
  links_.resize(n);
  omega_scratch_.resize(n);
  vel_scratch_.resize(n);
  contact_force_.assign(n, Eigen::Vector3d::Zero());
  contact_moment_.assign(n, Eigen::Vector3d::Zero());
  contact_normal_.assign(n, 0);
  external_force_.assign(n, Eigen::Vector3d::Zero());
  external_torque_.assign(n, Eigen::Vector3d::Zero());
  touching_.assign(n, 0);
  world_to_local_.resize(n);
  local_origin_.resize(n);
  if (need_links_) read_links();
  last_links_ = links_;
  for (Imu& s : imus_) {
    const LinkState& l = links_[s.link];
    s.last_velocity = point_velocity(s.link, l.com + l.rotation * s.com_from_sensor.translation());
  }
  for (Sensor& s : sensors_) {  // the readings at the start: at rest, no contact force yet
    double* out = values_.data() + s.first_value;
    if (s.kind == SensorKind::Imu) measure_imu(imus_[s.index], out);
    if (s.kind == SensorKind::ForceTorque) measure_force_torque(fts_[s.index], out);
    if (s.kind == SensorKind::Contact) measure_contact(contacts_[s.index], out);
  }
}

void SensorBank::read_links() {
  btMultiBody& body = mb_.body();
  body.forwardKinematics(world_to_local_, local_origin_);  // arrays sized at construction: no allocation
  body.compTreeLinkVelocities(omega_scratch_.data(), vel_scratch_.data());
  for (size_t k = 0; k < links_.size(); ++k) {
    LinkState& l = links_[k];
    const btQuaternion q = world_to_local_[int(k)].inverse();
    l.rotation = Eigen::Quaterniond(q.w(), q.x(), q.y(), q.z()).toRotationMatrix();
    l.com = eig(local_origin_[int(k)]);
    l.v = l.rotation * eig(vel_scratch_[k]);
    l.w = l.rotation * eig(omega_scratch_[k]);
    l.momentum = link_mass_[k] * l.v;
    l.angular_momentum = l.rotation * link_inertia_[k].cwiseProduct(l.rotation.transpose() * l.w);
  }
}

void SensorBank::read_contacts() {
  for (size_t k = 0; k < contact_force_.size(); ++k) {
    contact_force_[k].setZero();
    contact_moment_[k].setZero();
    contact_normal_[k] = 0;
    touching_[k] = 0;
  }
  const btMultiBody* body = &mb_.body();
  auto slot = [&](const btCollisionObject* o) {
    const btMultiBodyLinkCollider* c = btMultiBodyLinkCollider::upcast(o);
    return c && c->m_multiBody == body ? c->m_link + 1 : -1;
  };
  btDispatcher* dispatcher = mb_.world().getDispatcher();
  for (int m = 0; m < dispatcher->getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher->getManifoldByIndexInternal(m);
    const int a = slot(manifold->getBody0()), b = slot(manifold->getBody1());
    if (a < 0 && b < 0) continue;
    for (int p = 0; p < manifold->getNumContacts(); ++p) {
      const btManifoldPoint& pt = manifold->getContactPoint(p);
      if (pt.getDistance() > kContactSlop && pt.m_appliedImpulse <= 0) continue;
      // The impulses push body0 along the normal (from body1 to body0) and the friction directions.
      const Eigen::Vector3d f =
          (eig(pt.m_normalWorldOnB) * pt.m_appliedImpulse + eig(pt.m_lateralFrictionDir1) * pt.m_appliedImpulseLateral1 +
           eig(pt.m_lateralFrictionDir2) * pt.m_appliedImpulseLateral2) /
          dt_;
      const double normal = pt.m_appliedImpulse / dt_;
      if (a >= 0) {
        contact_force_[a] += f;
        contact_moment_[a] += eig(pt.getPositionWorldOnA()).cross(f);
        contact_normal_[a] += normal;
        touching_[a] = 1;
      }
      if (b >= 0) {
        contact_force_[b] -= f;
        contact_moment_[b] -= eig(pt.getPositionWorldOnB()).cross(f);
        contact_normal_[b] += normal;
        touching_[b] = 1;
      }
    }
  }
}

Eigen::Vector3d SensorBank::point_velocity(int link, const Eigen::Vector3d& p) const {
  const LinkState& l = links_[link];
  return l.v + l.w.cross(p - l.com);
}

void SensorBank::update() {
  if (sensors_.empty()) return;
  if (need_links_) {
    std::swap(links_, last_links_);
    read_links();
  }
  if (need_contacts_) read_contacts();
  for (Sensor& s : sensors_) {
    double* out = values_.data() + s.first_value;
    if (s.kind == SensorKind::Imu) measure_imu(imus_[s.index], out);
    if (s.kind == SensorKind::ForceTorque) measure_force_torque(fts_[s.index], out);
    if (s.kind == SensorKind::Contact) measure_contact(contacts_[s.index], out);
    for (size_t k = 0; k < s.noise.size(); ++k) {
      const GaussianNoise& g = s.noise[k];
      if (g.stddev != 0) out[k] += g.stddev * normal_(rng_);
      out[k] += g.mean + s.bias[k];
    }
  }
}

void SensorBank::measure_imu(Imu& s, double* out) {
  const LinkState& l = links_[s.link];
  const Eigen::Matrix3d world_from_sensor = l.rotation * s.com_from_sensor.linear();
  const Eigen::Vector3d v = point_velocity(s.link, l.com + l.rotation * s.com_from_sensor.translation());
  const Eigen::Vector3d a = (v - s.last_velocity) / dt_;
  s.last_velocity = v;
  const Eigen::Quaterniond q(world_from_sensor);
  const Eigen::Vector3d w = world_from_sensor.transpose() * l.w;
  const Eigen::Vector3d f = world_from_sensor.transpose() * (a - gravity_);
  const double values[10] = {q.x(), q.y(), q.z(), q.w(), w.x(), w.y(), w.z(), f.x(), f.y(), f.z()};
  std::copy(values, values + 10, out);
}

void SensorBank::measure_force_torque(const ForceTorque& s, double* out) const {
  const LinkState& child = links_[s.child];
  const Eigen::Vector3d p = child.com + child.rotation * s.com_from_joint.translation();  // the joint's origin
  // Newton-Euler on the subtree: the joint's wrench on it is its momentum change less its weight and contacts.
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment = Eigen::Vector3d::Zero();
  for (int k : s.subtree) {
    const LinkState& now = links_[k];
    const LinkState& before = last_links_[k];
    const Eigen::Vector3d weight = gravity_off_[k] ? Eigen::Vector3d::Zero() : Eigen::Vector3d(link_mass_[k] * gravity_);
    const Eigen::Vector3d net = (now.momentum - before.momentum) / dt_;
    const Eigen::Vector3d f = net - weight - contact_force_[k] - external_force_[k];
    force += f;
    moment += (now.angular_momentum - before.angular_momentum) / dt_ + (now.com - p).cross(net - weight) -
              (contact_moment_[k] - p.cross(contact_force_[k])) - (now.com - p).cross(external_force_[k]) -
              external_torque_[k];
  }
  force *= s.sign;
  moment *= s.sign;
  Eigen::Matrix3d world_from_frame = child.rotation * s.com_from_joint.linear();
  if (s.frame == WrenchFrame::Parent) {
    world_from_frame = links_[s.parent].rotation * s.parent_com_from_link;
  } else if (s.frame == WrenchFrame::Sensor) {
    const Eigen::Vector3d origin = p + world_from_frame * s.joint_from_sensor.translation();
    moment -= (origin - p).cross(force);
    world_from_frame = world_from_frame * s.joint_from_sensor.linear();
  }
  const Eigen::Vector3d f = world_from_frame.transpose() * force, t = world_from_frame.transpose() * moment;
  const double values[6] = {f.x(), f.y(), f.z(), t.x(), t.y(), t.z()};
  std::copy(values, values + 6, out);
}

void SensorBank::add_external_wrench(int link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque) {
  external_force_[size_t(link + 1)] += force;
  external_torque_[size_t(link + 1)] += torque;
}

void SensorBank::clear_external_wrenches() {
  for (auto& f : external_force_) f.setZero();
  for (auto& t : external_torque_) t.setZero();
}

void SensorBank::measure_contact(const Contact& s, double* out) const {
  out[0] = touching_[s.link] ? 1.0 : 0.0;
  out[1] = contact_normal_[s.link];
}

}  // namespace lcm_control::sim
