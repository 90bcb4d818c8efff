#include "sim_server/actuators.hpp"

#include "bus/hardware_wire.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <ctime>
#include <utility>

#include "control/angles.hpp"
#include "lcm_control/hardware_command_t.hpp"

namespace lcm_control::sim {

namespace {
// Friction is -f*tanh(v/v0): v0 small enough to look like Coulomb friction, large enough that the
// slope f/v0 stays a stable explicit damping for the joint's inertia.
constexpr double kMinFrictionSpeed = 1e-3;
constexpr double kUnlimitedEffort = 1e9;
// A position PID's D term goes through the solver (ImplicitJointDamper) once d*dt/I passes this. An explicit D term
// is unstable at d*dt/I = 2 for one joint alone, but near-coaxial joints of light links move modes lighter than any
// one joint's effective inertia (the upright Panda: largest mode 1.45x its largest joint's d*dt/I); below it the
// explicit term is cheaper (an always-active solver row costs a sweep of the whole body per iteration).
constexpr double kImplicitDamping = 0.25;

double finite_or(double v, double fallback) { return std::isfinite(v) ? v : fallback; }

}  // namespace

const char* to_string(ActuatorMode m) {
  switch (m) {
    case ActuatorMode::PositionPid: return "position PID";
    case ActuatorMode::PositionDirect: return "position direct";
    case ActuatorMode::VelocityPid: return "velocity PID";
    case ActuatorMode::VelocityMotor: return "velocity motor";
    case ActuatorMode::Effort: return "effort";
  }
  return "?";
}

Actuators::Actuators(const RobotModel& model, Multibody& mb) : mb_(mb) {
  const double dt = mb.dt();
  for (const TransmissionSpec& t : model.transmissions) {
    const int k = mb.joint_index(t.joint);
    if (k < 0)
      throw ModelError(fmt::format("{}: transmission '{}': joint '{}' is not a moving joint of the robot",
                                   model.urdf_path, t.name, t.joint));
    const MultibodyJoint& mj = mb.joints()[k];
    const Joint& j = *mj.urdf;
    Actuator a;
    a.name = t.actuator;
    a.joint = t.joint;
    a.map = t.map;
    a.link = mj.link;
    a.inertia = mj.effective_inertia;
    a.continuous = j.type == JointType::Continuous;
    a.effort_limit = j.effort_limit;
    a.velocity_limit = j.velocity_limit;
    a.passive = passive_for(mj, model.urdf_path, true);
    a.saturation = PositionSaturation(j.limits());
    const auto gains = model.pid_gains.find(t.joint);
    const bool with_gains = gains != model.pid_gains.end();
    const size_t n_offered = t.any_interface ? t.interfaces.size() : 1;  // ROS 1: the hardware takes the first
    bool brakeable = false;
    for (size_t k = 0; k < n_offered; ++k) {
      const Interface i = t.interfaces[k];
      const int8_t w = lcm_control::wire_mode(i);
      ActuatorMode m = ActuatorMode::Effort;
      if (i == Interface::Position) m = with_gains ? ActuatorMode::PositionPid : ActuatorMode::PositionDirect;
      if (i == Interface::Velocity) m = with_gains ? ActuatorMode::VelocityPid : ActuatorMode::VelocityMotor;
      a.offered[w] = true;
      a.mode_for[w] = m;
      a.has_pid = a.has_pid || m == ActuatorMode::PositionPid || m == ActuatorMode::VelocityPid;
      // Direct position is kinematic, as in Gazebo (a capped dead-beat motor would overshoot once it saturates);
      // the velocity motor is capped by the effort limit; a PID with soft gains would let a held joint drift, so
      // PID and effort modes get a brake.
      if (m == ActuatorMode::PositionDirect && !a.position_motor)
        a.position_motor = mb.add_motor(a.link, kUnlimitedEffort * dt);
      else if (m == ActuatorMode::VelocityMotor && !a.velocity_motor)
        a.velocity_motor = mb.add_motor(a.link, finite_or(a.effort_limit, kUnlimitedEffort) * dt);
      else
        brakeable = true;
    }
    a.wire_mode = a.next_wire_mode = lcm_control::wire_mode(t.interfaces.front());
    a.mode = a.mode_for[a.wire_mode];
    if (a.has_pid) a.pid.set_gains(gains->second);
    if (brakeable) a.brake = mb.add_motor(a.link, finite_or(a.effort_limit, kUnlimitedEffort) * dt);
    const bool pid_position = a.offered[hardware_command_t::MODE_POSITION] &&
                              a.mode_for[hardware_command_t::MODE_POSITION] == ActuatorMode::PositionPid;
    if (pid_position || a.offered[hardware_command_t::MODE_EFFORT]) {
      a.damper = mb.add_damper(a.link);  // in the world now, so that putting it back later does not allocate
      a.damper_on = true;
    }
    choose_damping(a);
    if (a.damper && a.inertia > 0 && a.passive.damping * dt / a.inertia > kImplicitDamping)
      a.implicit_urdf_damping = std::exchange(a.passive.damping, 0.0);
    else
      cap_damping(a.passive, mj, model.urdf_path);
    a.position_motor_on = a.position_motor != nullptr;
    a.velocity_motor_on = a.velocity_motor != nullptr;
    a.braking = a.brake != nullptr;
    a.q = a.hold_position = mb.position(a.link);
    a.saturation.reset(a.q);
    actuators_.push_back(std::move(a));
  }
  for (const MultibodyJoint& mj : mb.joints())
    if (!model.transmission_for_joint(mj.urdf->name) &&
        (mj.urdf->damping > 0 || mj.urdf->friction > 0 || mj.urdf->spring))
      passive_.push_back(passive_for(mj, model.urdf_path, false));
}

Actuators::Passive Actuators::passive_for(const MultibodyJoint& mj, const std::string& urdf, bool actuated) {
  const double dt = mb_.dt();
  const Joint& j = *mj.urdf;
  Passive p;
  p.link = mj.link;
  p.friction = j.friction;
  p.damping = j.damping;
  if (j.spring) {
    p.stiffness = j.spring->stiffness;
    p.reference = j.spring->reference;
    if (!actuated) p.implicit = mb_.add_damper(mj.link);
    else if (mj.effective_inertia > 0 && p.stiffness * dt * dt > mj.effective_inertia)
      warnings_.push_back(fmt::format("{}: joint '{}': springStiffness {:g} with an actuator is applied explicitly and "
                                      "is too stiff for a {:g} s step with inertia {:g} (it may oscillate); a spring "
                                      "on a joint nothing drives has no such limit",
                                      urdf, j.name, p.stiffness, dt, mj.effective_inertia));
  }
  if (!actuated) cap_damping(p, mj, urdf);
  p.friction_speed =
      mj.effective_inertia > 0 ? std::max(kMinFrictionSpeed, 2 * p.friction * dt / mj.effective_inertia) : 1.0;
  return p;
}

void Actuators::cap_damping(Passive& p, const MultibodyJoint& mj, const std::string& urdf) {
  const double dt = mb_.dt();
  if (p.implicit || mj.effective_inertia <= 0 || p.damping * dt <= mj.effective_inertia) return;
  p.damping = mj.effective_inertia / dt;
  warnings_.push_back(fmt::format("{}: joint '{}': damping {:g} is too stiff for a {:g} s step with inertia {:g}; "
                                  "simulated with {:g}",
                                  urdf, mj.urdf->name, mj.urdf->damping, dt, mj.effective_inertia, p.damping));
}

bool Actuators::offers(int i, int8_t wire_mode) const {
  return wire_mode > 0 && wire_mode < kWireModes && actuators_[i].offered[wire_mode];
}

std::string Actuators::describe(int i) const {
  const Actuator& a = actuators_[i];
  std::string how;
  switch (a.mode) {
    case ActuatorMode::PositionPid:
    case ActuatorMode::VelocityPid: {
      const PidGains& g = a.pid.gains();
      how = fmt::format("{} to effort (pid_gains p {:g} i {:g} d {:g} i_clamp [{:g}, {:g}]{})", to_string(a.mode), g.p,
                        g.i, g.d, g.i_clamp_min, g.i_clamp_max, g.antiwindup ? " antiwindup" : "");
      break;
    }
    case ActuatorMode::PositionDirect:
      how = "position direct (no pid_gains): the joint follows the command kinematically (a stiff motor whose "
            "force is reported as the effort)";
      break;
    case ActuatorMode::VelocityMotor:
      how = "velocity motor (no pid_gains), capped at the effort limit";
      break;
    case ActuatorMode::Effort:
      how = "effort, applied directly";
      break;
  }
  std::string also;
  for (int8_t w = 1; w < kWireModes; ++w)
    if (a.offered[w] && w != a.wire_mode)
      also += fmt::format("{}{} ({})", also.empty() ? "; switches on command to " : ", ", wire_mode_name(w),
                          to_string(a.mode_for[w]));
  return fmt::format("actuator '{}' -> joint '{}': {}{}; reduction {:g}, offset {:g}, effort limit {:g}, velocity "
                     "limit {:g}",
                     a.name, a.joint, how, also, a.map.reduction, a.map.offset, a.effort_limit, a.velocity_limit);
}

bool Actuators::set_command(int i, int8_t wire_mode, double value, double damping) {
  Actuator& a = actuators_[i];
  a.commanded = wire_mode != hardware_command_t::MODE_NONE;
  if (!a.commanded) return true;
  if (!offers(i, wire_mode)) {
    a.commanded = false;
    ++a.rejected;
    return false;
  }
  a.next_wire_mode = wire_mode;
  switch (wire_mode) {
    case hardware_command_t::MODE_POSITION: a.command = a.map.actuator_to_joint_position(value); break;
    case hardware_command_t::MODE_VELOCITY: a.command = a.map.actuator_to_joint_velocity(value); break;
    default:
      a.command = a.map.actuator_to_joint_effort(value);
      a.effort_damping = std::isfinite(damping) && damping > 0 ? a.map.actuator_to_joint_damping(damping) : 0.0;
      a.implicit_effort_d = a.damper && a.inertia > 0 && a.effort_damping * mb_.dt() / a.inertia > kImplicitDamping;
      break;
  }
  return true;
}

void Actuators::set_e_stop(bool engaged) {
  if (engaged && !e_stop_)
    for (Actuator& a : actuators_) {
      a.hold_position = a.q;
      a.holding = true;
    }
  e_stop_ = engaged;
}

bool Actuators::set_gains(int i, const PidGains& g) {
  if (!actuators_[i].has_pid) return false;
  actuators_[i].pid.set_gains(g);
  choose_damping(actuators_[i]);
  return true;
}

void Actuators::choose_damping(Actuator& a) {
  a.implicit_d = a.damper && a.inertia > 0 && a.pid.gains().d * mb_.dt() / a.inertia > kImplicitDamping;
}

double Actuators::position_goal(Actuator& a, bool hold, double dt) {
  if (hold) {
    a.saturation.reset(a.hold_position);
    return a.hold_position;
  }
  return a.saturation.enforce(a.command, dt);
}

void Actuators::set_in_world(btMultiBodyJointMotor* motor, bool& in_world, bool on) {
  if (!motor || on == in_world) return;
  // The motor was in the world when the solver buffers were sized, so adding it back does not allocate.
  if (on)
    mb_.world().addMultiBodyConstraint(motor);
  else
    mb_.world().removeMultiBodyConstraint(motor);
  in_world = on;
}

btMultiBodyJointMotor* Actuators::active_motor(const Actuator& a) const {
  if (a.mode == ActuatorMode::PositionDirect) return a.position_motor;
  if (a.mode == ActuatorMode::VelocityMotor) return a.velocity_motor;
  return nullptr;
}

void Actuators::switch_mode(Actuator& a, int8_t wire_mode) {
  a.wire_mode = wire_mode;
  a.mode = a.mode_for[wire_mode];
  a.pid.reset();
  a.have_last_goal = false;
  a.saturation.reset(a.q);  // a position goal moves from where the joint is, at most at the velocity limit
}

namespace {
int64_t now_ns() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}
}  // namespace

int64_t Actuators::take_work_ns(int i) { return std::exchange(actuators_[size_t(i)].work_ns, 0); }

void Actuators::apply(double dt) {
  int64_t mark = now_ns();
  for (Actuator& a : actuators_) {
    apply_one(a, dt);
    const int64_t t = now_ns();
    a.work_ns += t - mark;
    mark = t;
  }
  for (const Passive& p : passive_) mb_.add_torque(p.link, passive_torque(p, mb_.position(p.link), mb_.velocity(p.link)));
}

void Actuators::apply_one(Actuator& a, double dt) {
  {
    const bool hold = e_stop_ || hold_all_ || !a.commanded;
    if (hold && !a.holding) a.hold_position = a.q;
    a.holding = hold;
    const double q = a.q = mb_.position(a.link), qd = a.qd = mb_.velocity(a.link);
    if (a.commanded && a.next_wire_mode != a.wire_mode) switch_mode(a, a.next_wire_mode);
    set_in_world(a.position_motor, a.position_motor_on, a.mode == ActuatorMode::PositionDirect);
    set_in_world(a.velocity_motor, a.velocity_motor_on, a.mode == ActuatorMode::VelocityMotor);
    const bool pid_d = a.mode == ActuatorMode::PositionPid && a.implicit_d;
    const bool effort_d = a.mode == ActuatorMode::Effort && a.implicit_effort_d && !hold;
    const double c = a.implicit_urdf_damping;
    set_in_world(a.damper, a.damper_on, pid_d || effort_d || c > 0);
    if (c > 0 && !pid_d && !effort_d) a.damper->set(c, 0.0, -kUnlimitedEffort, kUnlimitedEffort);
    const bool brakeable_mode = a.mode != ActuatorMode::PositionDirect && a.mode != ActuatorMode::VelocityMotor;
    set_in_world(a.brake, a.braking, brakeable_mode && brakes_ && !e_stop_ && (hold_all_ || !a.commanded));
    if (a.braking) {
      a.brake->setPositionTarget(a.hold_position, 1.0);
      a.brake->setVelocityTarget(0, 1.0);
    }
    const double e_max = a.effort_limit;
    a.effort = 0;
    switch (a.mode) {
      case ActuatorMode::PositionPid: {
        const double goal = position_goal(a, hold, dt);
        const double error = a.continuous ? shortest_angular_distance(q, goal) : goal - q;
        const double u = a.pid.compute(error, dt);
        if (!pid_d) {
          a.effort = clamp_abs(u, e_max);
        } else {
          // d*(goal rate - v_next) in the solver instead of d*de/dt = d*(goal rate - v_now) here; together within
          // the effort limit; the URDF's damping c (towards 0) in the same row.
          const double step = a.continuous ? shortest_angular_distance(a.last_goal, goal) : goal - a.last_goal;
          const double goal_rate = a.have_last_goal ? step / dt : 0.0;
          a.effort = clamp_abs(u - a.pid.last_d_term(), e_max);
          const double limit = std::isfinite(e_max) ? e_max : kUnlimitedEffort;
          const double d = a.pid.gains().d;
          a.damper->set(d + c, d * goal_rate / (d + c), -limit - a.effort, limit - a.effort);
        }
        a.last_goal = goal;
        a.have_last_goal = true;
        break;
      }
      case ActuatorMode::PositionDirect: {
        double goal = position_goal(a, hold, dt);
        if (a.continuous) goal = q + shortest_angular_distance(q, goal);
        a.position_motor->setPositionTarget(goal, 1.0);
        a.position_motor->setVelocityTarget(0, 1.0);
        break;
      }
      case ActuatorMode::VelocityPid: {
        const double goal = hold ? 0.0 : clamp_abs(a.command, a.velocity_limit);
        a.effort = clamp_abs(a.pid.compute(goal - qd, dt), e_max);
        break;
      }
      case ActuatorMode::VelocityMotor:
        a.velocity_motor->setPositionTarget(0, 0.0);
        a.velocity_motor->setVelocityTarget(hold ? 0.0 : clamp_abs(a.command, a.velocity_limit), 1.0);
        break;
      case ActuatorMode::Effort:
        if (hold) {
          a.effort = 0;
        } else if (!effort_d) {
          a.effort = clamp_abs(a.command, e_max);
        } else {
          // The command's -d*v_then as -d*v_next in the solver; together within the effort limit; the URDF's
          // damping in the same row.
          const double limit = std::isfinite(e_max) ? e_max : kUnlimitedEffort;
          a.effort = a.command + a.effort_damping * qd;
          a.damper->set(a.effort_damping + c, 0.0, -limit - a.effort, limit - a.effort);
        }
        break;
    }
    if (!std::isfinite(a.effort)) a.effort = 0;  // Bullet turns one Inf or NaN into NaN everywhere
    mb_.add_torque(a.link, a.effort + passive_torque(a.passive, q, qd));
  }
}

double Actuators::passive_torque(const Passive& p, double q, double qd) {
  const double friction = -p.friction * std::tanh(qd / p.friction_speed);
  if (p.implicit) {
    // -k*(q_next - ref) - d*v_next with q_next = q + dt*v_next: a damper of d + k*dt towards -k*(q - ref)/(d + k*dt).
    const double c = p.damping + p.stiffness * mb_.dt();
    p.implicit->set(c, c > 0 ? -p.stiffness * (q - p.reference) / c : 0.0, -kUnlimitedEffort, kUnlimitedEffort);
    return friction;
  }
  return friction - p.damping * qd - p.stiffness * (q - p.reference);
}

void Actuators::read(double dt) {
  int64_t mark = now_ns();
  for (Actuator& a : actuators_) {
    a.q = mb_.position(a.link);
    a.qd = mb_.velocity(a.link);
    btMultiBodyJointMotor* motor = active_motor(a);
    a.applied = motor ? motor->getAppliedImpulse(0) / dt : a.effort;
    if (a.braking) a.applied += a.brake->getAppliedImpulse(0) / dt;
    if (a.damper_on) a.applied += a.damper->applied_torque(dt);
    const int64_t t = now_ns();
    a.work_ns += t - mark;
    mark = t;
  }
}

double Actuators::position(int i) const {
  return actuators_[i].map.joint_to_actuator_position(actuators_[i].q);
}
double Actuators::velocity(int i) const {
  return actuators_[i].map.joint_to_actuator_velocity(actuators_[i].qd);
}
double Actuators::effort(int i) const { return actuators_[i].map.joint_to_actuator_effort(actuators_[i].applied); }

}  // namespace lcm_control::sim
