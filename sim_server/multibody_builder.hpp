// The robot model as a fixed-base btMultiBody in its own btMultiBodyDynamicsWorld:
// links in depth-first order with COM frames on the inertia's principal axes,
// fixed joints as fixed links, a collider on every link, limits that do not
// overshoot, each joint's own velocity limit, mimic joints coupled to their
// joint by a gear constraint (so they carry load), an initial pose inside the
// limits, and none of Bullet's hidden defaults (damping, sleeping, motors, the
// 100 rad/s velocity clamp).
#pragma once

#ifndef BT_USE_DOUBLE_PRECISION
#error "sim_server needs Bullet in double precision: use pkg-config bullet-float64 (it defines BT_USE_DOUBLE_PRECISION)"
#endif

#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyGearConstraint.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointMotor.h>
#include <BulletDynamics/Featherstone/btMultiBodyLinkCollider.h>
#include <btBulletDynamicsCommon.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "description/initial_positions.hpp"
#include "description/robot_model.hpp"
#include "sim_server/collision_shapes.hpp"
#include "sim_server/contact_solver.hpp"
#include "sim_server/implicit_damper.hpp"
#include "sim_server/limit_constraint.hpp"

namespace lcm_control::sim {

// One moving (revolute, continuous, prismatic) joint of the multibody.
struct MultibodyJoint {
  const Joint* urdf = nullptr;
  int link = -1;                       // Bullet link index
  double effective_inertia = 0;        // 1 / (M^-1)_jj at the initial pose: kg m^2 or kg
  SpeculativeJointLimit* limit = nullptr;  // null for continuous joints
  double max_velocity = 0;             // URDF velocity limit, 0: none
  btMultiBodyGearConstraint* gear = nullptr;  // a mimic joint's coupling to the joint it mimics
  int leader_link = -1;                       // that joint's Bullet link
};

// Where the robot lives: welded to the world at its root link (an arm; the default), or a free-floating base, as
// Gazebo leaves a model that has no joint to `world` (a mobile robot), usually on a ground plane.
struct WorldOptions {
  bool floating_base = false;
  bool ground = false;                // a plane at z = 0; contacts with friction 1, or a link's <mu1>
  Eigen::Vector3d base_position = Eigen::Vector3d::Zero();  // the root link frame's start, world frame (m)
  double base_yaw = 0;                                        // rad about z
  uint64_t noise_seed = 0;            // seeds the sensors' Gaussian noise (sim_server/sensors.hpp)
};

// How the root link is mounted. Auto is Gazebo's rule (ros_gz_sim create, spawn_model): welded when the URDF's root
// link is `world` (an arm's <link name="world"/> and fixed joint), free on the ground otherwise (a mobile base).
enum class BaseMount { Auto, Fixed, Floating };
bool floating_base_for(const RobotModel& model, BaseMount mount);

class Multibody {
 public:
  // Throws ModelError for a robot Bullet cannot take or an initial position naming no moving joint. A joint that
  // would start outside its limits starts clamped into them (a warning says so).
  Multibody(const RobotModel& model, double dt, const InitialPositions& initial = {}, const WorldOptions& world = {});
  ~Multibody();
  Multibody(const Multibody&) = delete;
  Multibody& operator=(const Multibody&) = delete;

  double dt() const { return dt_; }
  // One physics step of exactly dt; joint torques added before it are consumed. Afterwards every joint's
  // speed is within its URDF velocity limit (Bullet's own clamp is one value for the whole body).
  void step();

  const std::vector<MultibodyJoint>& joints() const { return joints_; }
  // Index into joints() of a moving joint, -1 if there is none of that name.
  int joint_index(const std::string& name) const;

  double position(int link) const { return body_->getJointPos(link); }
  // The effort (N*m or N) the gear applied to a mimic joint in the last step; 0 for other joints.
  double mimic_effort(int joint_index) const;
  double velocity(int link) const { return body_->getJointVel(link); }
  void add_torque(int link, double tau) { body_->addJointTorque(link, tau); }
  // A force (N) at the Bullet link's centre of mass and a torque (N*m), world frame, for the next step (-1: the base).
  void add_link_wrench(int link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque);
  // Sets a joint's position and velocity (tests, initial poses) and refreshes the cached kinematics.
  void set_state(int link, double q, double qd);
  // A joint motor on the link (impulse per step capped at max_impulse), owned and added to the world here.
  btMultiBodyJointMotor* add_motor(int link, double max_impulse);
  // An implicit damper on the link's joint (damping 0 until set), owned and added to the world here.
  ImplicitJointDamper* add_damper(int link);

  // Takes one throw-away step with every limit row (and every motor) active, then restores the state: Bullet
  // sizes its solver buffers to that high-water mark, so later steps do not allocate. Call after adding motors.
  void size_solver_buffers();

  // Floating base: the root link frame in the world, and its velocity (world frame: linear m/s, angular rad/s).
  bool floating_base() const { return !body_->hasFixedBase(); }
  const std::string& root_link() const { return model_root_; }
  Eigen::Isometry3d base_pose() const;
  Eigen::Vector3d base_linear_velocity() const;
  Eigen::Vector3d base_angular_velocity() const;

  // Pose of a URDF link frame and position of its centre of mass, in the world.
  Eigen::Isometry3d link_pose(const std::string& link) const;
  // Bullet's index of a URDF link (-1: the base); throws std::out_of_range for no link of that name.
  int link_index(const std::string& link) const { return link_index_.at(link); }
  // A URDF link's Bullet COM frame (its principal axes at its centre of mass) in the link frame.
  const Eigen::Isometry3d& link_from_com(const std::string& link) const { return link_from_com_.at(link); }
  Eigen::Vector3d com_position(const std::string& link) const;

  btMultiBody& body() { return *body_; }
  btMultiBodyDynamicsWorld& world() { return *world_; }
  // Findings worth a WARN (massless moving links, inertia fixes, damping capped for stability).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Initial positions outside the limits, clamped into them (one WARN each).
  const std::vector<std::string>& start_warnings() const { return start_warnings_; }
  // What the start did that the user should know (one INFO each): a floating base lifted out of the ground.
  const std::vector<std::string>& start_notes() const { return start_notes_; }

 private:
  void build(const RobotModel& model, const WorldOptions& world);
  void set_initial_positions(const RobotModel& model, const InitialPositions& initial);
  // A floating base whose collision shapes start inside the ground plane would be thrown up by Bullet's
  // penetration recovery: lift it so its lowest shape (AABB in the initial pose) rests on the plane.
  void rest_on_ground(const RobotModel& model);
  void compute_effective_inertias();
  void set_state_refresh();  // forward kinematics and collider transforms after a state change

  double dt_;
  std::unique_ptr<btDefaultCollisionConfiguration> collision_config_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btBroadphaseInterface> broadphase_;
  std::unique_ptr<ContactSolver> solver_;
  std::unique_ptr<btMultiBodyDynamicsWorld> world_;
  std::unique_ptr<btMultiBody> body_;
  ShapeStore shapes_;
  std::vector<std::unique_ptr<btMultiBodyLinkCollider>> colliders_;
  std::unique_ptr<btCollisionObject> ground_;
  std::string model_root_;
  std::vector<std::unique_ptr<btMultiBodyConstraint>> constraints_;
  std::vector<MultibodyJoint> joints_;
  std::map<std::string, int> link_index_;               // URDF link -> Bullet link (-1: base)
  std::map<std::string, Eigen::Isometry3d> link_from_com_;  // URDF link frame -> its Bullet COM frame
  std::vector<std::string> warnings_, start_warnings_, start_notes_;
  // <turnGravityOff> links: Bullet link index (-1: base) and the force that cancels their weight, added each step.
  std::vector<std::pair<int, btVector3>> antigravity_;
};

}  // namespace lcm_control::sim
