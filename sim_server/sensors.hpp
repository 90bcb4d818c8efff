// The robot's declared sensors (description/sensors.hpp) measured on the multibody after every physics step, each
// in its own frame:
//  - IMU: orientation (sensor frame in the world), angular velocity [rad/s], and linear acceleration [m/s^2] with
//    gravity's reaction in it (+9.81 along the sensor's up at rest), from the sensor point's velocity change;
//  - force-torque: the wrench through the joint [N, N*m at the joint's origin], from the momentum balance of the links
//    below it (so the motor, limit, damping and friction forces the joint carries are all in it) less their weight and
//    the contact forces on them;
//  - contact: touching or not, and the total normal force [N] on the link.
// Declared Gaussian noise comes from one generator seeded at construction, so a lockstep run repeats bit for bit.
// update() is on the physics path: it neither allocates nor logs.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "description/robot_model.hpp"
#include "sim_server/multibody_builder.hpp"

namespace lcm_control::sim {

class SensorBank {
 public:
  // The simulated sensors of model.sensors, at the multibody's present state (a first IMU reading has no
  // acceleration but gravity's). `seed` seeds the noise.
  SensorBank(const RobotModel& model, Multibody& multibody, uint64_t seed = 0);

  // Measures every sensor after a physics step of the multibody's dt.
  void update();
  // A force at the centre of mass of Bullet link `link` (-1: the base) and a torque, world frame, applied in the
  // steps until the next clear (Simulation::apply_wrench): a force-torque sensor counts it as it counts contacts.
  void add_external_wrench(int link, const Eigen::Vector3d& force, const Eigen::Vector3d& torque);
  void clear_external_wrenches();

  bool empty() const { return names_.empty(); }
  // "<sensor>/<interface>" per value, sensors in model order, each kind's interfaces in sensor_interfaces() order.
  const std::vector<std::string>& names() const { return names_; }
  const std::vector<double>& values() const { return values_; }

 private:
  struct LinkState {
    Eigen::Vector3d com, v, w;  // world: COM position [m], COM velocity [m/s], angular velocity [rad/s]
    Eigen::Matrix3d rotation;   // world from COM frame
    Eigen::Vector3d momentum, angular_momentum;  // m v and I w about the COM, world
  };
  struct Imu {
    int link;                          // Bullet link + 1 (base at 0)
    Eigen::Isometry3d com_from_sensor;
    Eigen::Vector3d last_velocity;     // of the sensor point, world
  };
  struct ForceTorque {
    int child;                         // Bullet link + 1 of the joint's child link
    int parent;                        // Bullet link + 1 of its parent link
    Eigen::Isometry3d com_from_joint;  // the joint (child link) frame in the child's COM frame
    Eigen::Matrix3d parent_com_from_link;  // the parent link frame's rotation in the parent's COM frame
    Eigen::Isometry3d joint_from_sensor;
    WrenchFrame frame;
    double sign;                       // +1 the parent's wrench on the child, -1 the child's on the parent
    std::vector<int> subtree;          // Bullet link + 1 of the child and every link below it
  };
  struct Contact {
    int link;  // Bullet link + 1
  };
  struct Sensor {
    SensorKind kind;
    int index;                         // into imus_, fts_ or contacts_
    size_t first_value;
    std::vector<GaussianNoise> noise;  // per value
    std::vector<double> bias;          // per value, drawn once
  };

  void read_links();
  void read_contacts();
  Eigen::Vector3d point_velocity(int link, const Eigen::Vector3d& p) const;
  void measure_imu(Imu& s, double* out);
  void measure_force_torque(const ForceTorque& s, double* out) const;
  void measure_contact(const Contact& s, double* out) const;

  Multibody& mb_;
  double dt_;
  Eigen::Vector3d gravity_;
  std::vector<double> link_mass_;       // per Bullet link + 1
  std::vector<Eigen::Vector3d> link_inertia_;  // principal, COM frame
  std::vector<char> gravity_off_;
  std::vector<LinkState> links_, last_links_;  // per Bullet link + 1
  btAlignedObjectArray<btQuaternion> world_to_local_;
  btAlignedObjectArray<btVector3> local_origin_;
  // Contact forces on each link from the last step, per Bullet link + 1 (base at 0), world frame: total force [N],
  // its moment about the world origin [N*m], normal force [N], touching.
  std::vector<Eigen::Vector3d> contact_force_, contact_moment_;
  std::vector<Eigen::Vector3d> external_force_, external_torque_;  // per Bullet link + 1
  std::vector<double> contact_normal_;
  std::vector<char> touching_;
  std::vector<btVector3> omega_scratch_, vel_scratch_;
  std::vector<Imu> imus_;
  std::vector<ForceTorque> fts_;
  std::vector<Contact> contacts_;
  std::vector<Sensor> sensors_;
  std::vector<std::string> names_;
  std::vector<double> values_;
  std::mt19937_64 rng_;
  std::normal_distribution<double> normal_{0.0, 1.0};
  bool need_links_ = false, need_contacts_ = false;
};

}  // namespace lcm_control::sim
