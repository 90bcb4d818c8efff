// The simulated hardware behind each transmission: it takes actuator-space
// commands in the mode its hardwareInterface declares (a <ros2_control> joint:
// in any command interface it offers, switching at the step the mode changes)
// and turns them, every
// physics step, into joint torques or motor targets with gazebo_ros_control's
// semantics (PID to effort with pid_gains, direct without), plus what that
// plugin leaves out: transmissions, position/velocity/effort limits, URDF
// damping and friction, e-stop latch and hold, and a brake that keeps an
// uncommanded effort or velocity-PID joint where it is.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "control/joint_limits.hpp"
#include "control/pid.hpp"
#include "description/robot_model.hpp"
#include "sim_server/played_hardware.hpp"
#include "sim_server/multibody_builder.hpp"

namespace lcm_control::sim {

enum class ActuatorMode { PositionPid, PositionDirect, VelocityPid, VelocityMotor, Effort };
const char* to_string(ActuatorMode m);

class Actuators final : public PlayedHardware {
 public:
  // Reads the transmissions (in URDF order) and pid_gains; adds every motor the offered modes need (switching modes
  // then only takes motors out of the world or puts them back, which does not allocate).
  Actuators(const RobotModel& model, Multibody& multibody);

  int size() const override { return int(actuators_.size()); }
  const std::string& name(int i) const override { return actuators_[i].name; }
  const std::string& joint(int i) const override { return actuators_[i].joint; }
  ActuatorMode mode(int i) const { return actuators_[i].mode; }
  int8_t wire_mode(int i) const override { return actuators_[i].wire_mode; }  // hardware_command_t::MODE_*
  bool offers(int i, int8_t wire_mode) const override;
  const char* mode_name(int i) const override { return to_string(actuators_[i].mode); }
  // Commands in a mode the joint does not offer, since the start (each held the actuator for that step).
  int64_t rejected(int i) const { return actuators_[i].rejected; }
  // One line per actuator for the INFO log: mode, reduction, limits, gains.
  std::string describe(int i) const;
  // Whether a position PID's D term, or the damping of the effort command, is applied implicitly (d*dt/I above
  // kImplicitDamping).
  bool implicit_derivative(int i) const {
    return actuators_[i].mode == ActuatorMode::Effort ? actuators_[i].implicit_effort_d : actuators_[i].implicit_d;
  }
  // Findings worth a WARN (damping capped so the explicit damping torque stays stable).
  const std::vector<std::string>& warnings() const { return warnings_; }

  // Commands in actuator units; MODE_NONE holds. Another offered mode switches the actuator at the next physics
  // step: a position servo starts from the measured position (rate-limited from there), a PID starts afresh, the
  // previous mode's motor leaves the world. A mode not offered holds and returns false. An effort command's
  // `damping` (its -damping * velocity part) is applied from the velocity at the end of the step, as a position PID's
  // D term is, once damping*dt/I passes kImplicitDamping. Real-time safe.
  bool set_command(int i, int8_t wire_mode, double value, double damping = 0) override;
  // Watchdog or lost controller: every actuator holds while set.
  void set_hold_all(bool hold) override { hold_all_ = hold; }
  bool hold_all() const override { return hold_all_; }
  // Brakes (default on): an effort, velocity-PID or position-PID actuator nobody commands, or held by the watchdog,
  // is held at its position by a motor capped at the effort limit, so an arm does not sag before its controllers
  // start and does not drift on soft gains while its controller manager is gone. Off: such a joint is limp (effort,
  // velocity) or held by its PID alone, as in Gazebo. The e-stop never brakes (velocity and effort get 0).
  void set_brakes(bool on) { brakes_ = on; }
  bool brakes() const { return brakes_; }
  // Position actuators latch their position when it engages; velocity and effort get 0.
  void set_e_stop(bool engaged) override;
  bool e_stop() const override { return e_stop_; }

  bool has_pid(int i) const override { return actuators_[i].has_pid; }
  const PidGains& gains(int i) const override { return actuators_[i].pid.gains(); }
  // Joint-space gains of a PID actuator, used from the next physics step on; false for direct modes.
  bool set_gains(int i, const PidGains& g) override;

  // The real-time path, around every physics step: no allocation, logging or locks.
  void apply(double dt);  // torques and motor targets for the coming step
  void read(double dt);   // state and applied effort after it

  // The nanoseconds apply() and read() spent on actuator i since the last call (its hardware component's share of
  // the step: ros2_control's per-component read/write time).
  int64_t take_work_ns(int i);

  // State after the last step, in actuator units.
  double position(int i) const override;
  double velocity(int i) const override;
  double effort(int i) const override;
  // The same in joint units.
  double joint_position(int i) const { return actuators_[i].q; }
  double joint_velocity(int i) const { return actuators_[i].qd; }
  double joint_effort(int i) const { return actuators_[i].applied; }

 private:
  // URDF damping and friction of a moving joint (torques -d*v and -f*tanh(v/friction_speed)) and its Gazebo spring
  // (-stiffness*(q - reference)). A joint nothing drives takes its spring and damping through `implicit`, solved at
  // the end of the step (stable for any stiffness, as Gazebo's implicitSpringDamper); an actuated one explicitly.
  struct Passive {
    int link = -1;
    double damping = 0, friction = 0, friction_speed = 1;
    double stiffness = 0, reference = 0;
    ImplicitJointDamper* implicit = nullptr;
  };

  static constexpr int kWireModes = 4;  // MODE_NONE .. MODE_EFFORT
  struct Actuator;
  void apply_one(Actuator& a, double dt);

  struct Actuator {
    std::string name, joint;
    ActuatorMode mode = ActuatorMode::Effort;
    int8_t wire_mode = 0;
    int8_t next_wire_mode = 0;               // the mode of the newest command; apply() switches to it
    int64_t work_ns = 0;                     // in apply() and read() since take_work_ns()
    bool offered[kWireModes] = {};           // by wire mode
    ActuatorMode mode_for[kWireModes] = {};  // how each offered wire mode is played
    int64_t rejected = 0;
    SimpleTransmission map;
    int link = -1;
    bool continuous = false;
    double effort_limit = 0, velocity_limit = 0;
    Passive passive;
    PositionSaturation saturation;
    bool has_pid = false;
    Pid pid;
    // Each in the world only while its mode (or braking) uses it; all are there when the solver buffers are sized.
    btMultiBodyJointMotor* position_motor = nullptr;  // position direct
    btMultiBodyJointMotor* velocity_motor = nullptr;  // velocity motor
    btMultiBodyJointMotor* brake = nullptr;
    // Position PID, and an effort command's damping: its D term as an implicit damper while d*dt/I (I: the joint's
    // effective inertia) is above kImplicitDamping, where an explicit one nears instability.
    ImplicitJointDamper* damper = nullptr;
    double inertia = 0;
    bool implicit_d = false;
    double effort_damping = 0;  // joint units: the -d*v part of `command` in effort mode
    bool implicit_effort_d = false;
    // The URDF <dynamics damping> when c*dt/I passes kImplicitDamping and the joint has a damper: in the solver, in
    // every mode and while held, instead of the explicit -c*v (then passive.damping is 0).
    double implicit_urdf_damping = 0;
    bool position_motor_on = false, velocity_motor_on = false, braking = false, damper_on = false;
    double last_goal = 0;
    bool have_last_goal = false;
    bool commanded = false;  // false: nobody commands it (MODE_NONE or none yet)
    double command = 0;      // joint units
    bool holding = true;
    double hold_position = 0;
    double q = 0, qd = 0, effort = 0, applied = 0;
  };

  double position_goal(Actuator& a, bool hold, double dt);
  void choose_damping(Actuator& a);
  void switch_mode(Actuator& a, int8_t wire_mode);
  void set_in_world(btMultiBodyJointMotor* motor, bool& in_world, bool on);
  btMultiBodyJointMotor* active_motor(const Actuator& a) const;
  Passive passive_for(const MultibodyJoint& j, const std::string& urdf, bool actuated);
  // Lowers an explicit damping too stiff for the step to the stable c = I/dt, with a warning.
  void cap_damping(Passive& p, const MultibodyJoint& mj, const std::string& urdf);
  // The explicit part: friction, and damping and spring unless `implicit` takes them (then sets it for the step).
  double passive_torque(const Passive& p, double q, double qd);

  Multibody& mb_;
  std::vector<Actuator> actuators_;
  std::vector<Passive> passive_;  // joints without a transmission

  bool hold_all_ = false, e_stop_ = false, brakes_ = true;
  std::vector<std::string> warnings_;
};

}  // namespace lcm_control::sim
