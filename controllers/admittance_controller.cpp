// ROS 2's admittance_controller/AdmittanceController (ros2_controllers): the tool yields to a force-torque sensor's
// external wrench as a mass-spring-damper, M a + D v + K x = F (per selected axis of the base frame; D = 2 zeta
// sqrt(K M)), around the pose its joint references put it at; the joints are commanded on position to the pose
// displaced by x, found by damped least squares over the URDF chain from kinematics.base to kinematics.tip with
// Orocos KDL (liborocos-kdl-dev: the library ROS's kinematics_interface_kdl plugin wraps). Chainable: each joint is
// the reference interface "<name>/<joint>" (position), which a JointTrajectoryController writes through its
// command_joints; not chained, the references are the joints' positions when it started, then what comes on
// <name>/command (float64_array_t, one position per joint: ROS 2's ~/joint_references). The sensor reads what the
// tool applies on it (SDF's child_to_parent, Gazebo's default): the external wrench is that less the tool's weight,
// gravity_compensation.CoG.force [N] at CoG.pos [m, the sensor's frame].
#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <memory>

#include "controllers/factories.hpp"

namespace lcm_control::cm {

namespace {

KDL::Vector kdl(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
KDL::Frame kdl(const Eigen::Isometry3d& f) {
  const Eigen::Matrix3d& r = f.linear();
  return {KDL::Rotation(r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)),
          kdl(f.translation())};
}
Eigen::Matrix3d eig(const KDL::Rotation& r) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m(i, j) = r(i, j);
  return m;
}

// The URDF chain from `base` down to `tip` as KDL builds it from a URDF (kdl_parser's rule: each joint a segment whose
// joint turns about its axis at its origin); `moving` gets the moving joints' names, base to tip. Throws naming the
// key and the links when `tip` is not below `base`.
KDL::Chain chain_between(const RobotModel& m, const std::string& base, const std::string& tip, const Params& p,
                         const std::string& key, std::vector<std::string>& moving) {
  std::vector<const Joint*> up;
  for (std::string link = tip; link != base;) {
    const Link* l = m.link(link);
    if (!l)
      throw p.error(key, fmt::format("no link '{}' in {}", link, m.urdf_path));
    if (l->parent_joint.empty())
      throw p.error(key, fmt::format("link '{}' is not below '{}' in {}: give kinematics.base an ancestor of the tip",
                                     tip, base, m.urdf_path));
    const Joint* j = m.joint(l->parent_joint);
    up.push_back(j);
    link = j->parent_link;
  }
  KDL::Chain chain;
  for (auto it = up.rbegin(); it != up.rend(); ++it) {
    const Joint& j = **it;
    const KDL::Frame origin = kdl(j.origin);
    KDL::Joint joint(j.name, KDL::Joint::Fixed);
    if (j.type == JointType::Revolute || j.type == JointType::Continuous)
      joint = KDL::Joint(j.name, origin.p, origin.M * kdl(j.axis), KDL::Joint::RotAxis);
    else if (j.type == JointType::Prismatic)
      joint = KDL::Joint(j.name, origin.p, origin.M * kdl(j.axis), KDL::Joint::TransAxis);
    if (j.type != JointType::Fixed) moving.push_back(j.name);
    chain.addSegment(KDL::Segment(j.child_link, joint, origin));
  }
  return chain;
}

std::array<double, 6> six(const Params& p, const YAML::Node& n, const std::string& key, double fallback) {
  std::array<double, 6> out;
  out.fill(fallback);
  if (!n) return out;
  if (!n.IsSequence() || n.size() != 6)
    throw p.error(key, "expected 6 values: x, y, z, rx, ry, rz (the base frame)");
  for (size_t k = 0; k < 6; ++k) {
    const std::string text = n[k].Scalar();
    if (text == "true" || text == "True") {
      out[k] = 1;
    } else if (text == "false" || text == "False") {
      out[k] = 0;
    } else {
      try {
        out[k] = n[k].as<double>();
      } catch (const YAML::Exception&) {
        throw p.error(key, fmt::format("entry {}: '{}' is not a number", k, text));
      }
    }
  }
  return out;
}

class AdmittanceController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const RobotModel& m = ctx.model();
    names_ = p.strings("joints");
    if (p.has("command_interfaces")) {
      const std::vector<std::string> c = p.strings("command_interfaces");
      if (c.front() != "position")
        throw p.error("command_interfaces", fmt::format("[{}]: this admittance controller commands [position]",
                                                        fmt::join(c, ", ")));
    }
    p.node("state_interfaces");
    p.node("chainable_command_interfaces");
    const YAML::Node kin = p.node("kinematics");
    if (!kin || !kin["base"] || !kin["tip"])
      throw p.error("kinematics", "give kinematics.base and kinematics.tip: the links the tool's chain runs between");
    const std::string base = kin["base"].as<std::string>(), tip = kin["tip"].as<std::string>();
    if (kin["plugin_name"] && kin["plugin_name"].as<std::string>() != "kinematics_interface_kdl/KinematicsInterfaceKDL")
      ctx.notes.push_back(fmt::format("{}/kinematics/plugin_name: '{}': the kinematics here are KDL's whatever it "
                                      "names",
                                      p.where(), kin["plugin_name"].as<std::string>()));
    lambda_ = kin["alpha"] ? kin["alpha"].as<double>() : 0.0005;
    std::vector<std::string> moving;
    chain_ = chain_between(m, base, tip, p, "kinematics", moving);
    if (moving != names_)
      throw p.error("joints", fmt::format("[{}]: the moving joints from '{}' to '{}' are [{}], in that order",
                                          fmt::join(names_, ", "), base, tip, fmt::join(moving, ", ")));
    for (const auto& n : names_) {
      joints_.push_back(ctx.claim(n, Interface::Position));
      refs_.push_back(ctx.export_reference(n, {Interface::Position, Interface::Velocity}, joints_.back()));
    }
    const YAML::Node ft = p.node("ft_sensor");
    if (!ft || !ft["name"]) throw p.error("ft_sensor", "give ft_sensor.name: the force-torque sensor at the tool");
    sensor_ = ctx.sensor(ft["name"].as<std::string>(), "ft_sensor", SensorKind::ForceTorque);
    const std::string frame = sensor_->frame_id;
    if (!m.link(frame))
      throw p.error("ft_sensor", fmt::format("sensor '{}' reports in frame '{}', which is no link of {}",
                                             sensor_->name, frame, m.urdf_path));
    // The sensor sits on the tool's chain (a wrist sensor): its frame is the end of one of the chain's segments,
    // so one forward kinematics serves both.
    sensor_segment_ = frame == base ? 0 : -1;
    for (unsigned k = 0; k < chain_.getNrOfSegments() && sensor_segment_ < 0; ++k)
      if (chain_.getSegment(k).getName() == frame) sensor_segment_ = int(k) + 1;
    if (sensor_segment_ < 0)
      throw p.error("ft_sensor", fmt::format("sensor '{}' reports in frame '{}', which is not on the chain from '{}' "
                                             "to '{}'",
                                             sensor_->name, frame, base, tip));
    filter_ = ft["filter_coefficient"] ? ft["filter_coefficient"].as<double>() : 1.0;
    if (!(filter_ > 0 && filter_ <= 1)) throw p.error("ft_sensor", "filter_coefficient: give a value in (0, 1]");
    if (const YAML::Node g = p.node("gravity_compensation"); g && g["CoG"]) {
      const YAML::Node cog = g["CoG"];
      if (cog["force"]) weight_ = cog["force"].as<double>();
      if (cog["pos"] && cog["pos"].IsSequence() && cog["pos"].size() == 3)
        cog_ = {cog["pos"][0].as<double>(), cog["pos"][1].as<double>(), cog["pos"][2].as<double>()};
    }
    p.node("control");
    p.node("fixed_world_frame");
    const YAML::Node a = p.node("admittance");
    if (!a) throw p.error("admittance", "give admittance: {selected_axes, mass, damping_ratio, stiffness} (6 each)");
    const auto axes = six(p, a["selected_axes"], "admittance/selected_axes", 1.0);
    const auto mass = six(p, a["mass"], "admittance/mass", NAN);
    const auto zeta = six(p, a["damping_ratio"], "admittance/damping_ratio", NAN);
    const auto k = six(p, a["stiffness"], "admittance/stiffness", NAN);
    for (size_t i = 0; i < 6; ++i) {
      selected_[i] = axes[i] != 0;
      if (!selected_[i]) continue;
      if (!(mass[i] > 0)) throw p.error("admittance/mass", fmt::format("axis {}: {} kg: give a mass > 0", i, mass[i]));
      if (!(k[i] >= 0) || !(zeta[i] >= 0))
        throw p.error("admittance", fmt::format("axis {}: stiffness and damping_ratio must be >= 0", i));
      mass_[i] = mass[i];
      stiffness_[i] = k[i];
      damping_[i] = 2 * zeta[i] * std::sqrt(k[i] * mass[i]);
    }
    const size_t n = names_.size();
    fk_ = std::make_unique<KDL::ChainFkSolverPos_recursive>(chain_);
    jac_solver_ = std::make_unique<KDL::ChainJntToJacSolver>(chain_);
    q_ = KDL::JntArray(n);
    q_measured_ = KDL::JntArray(n);
    jac_ = KDL::Jacobian(n);
    j_.resize(6, Eigen::Index(n));
    reference_.assign(n, 0.0);
    // Not chained: joint position references on <name>/command (ROS 2's ~/joint_references), one per joint.
    ctx.take_commands(true, n, [this](const double* v) {
      if (!running_ || chained_mode()) return;
      std::copy(v, v + reference_.size(), reference_.begin());
    });
  }

  void starting(const Time&) override {
    for (size_t k = 0; k < joints_.size(); ++k) {
      reference_[k] = joints_[k]->position;
      refs_[k]->command = joints_[k]->position;
    }
    x_.setZero();
    v_.setZero();
    wrench_.setZero();
    filtered_ = false;
  }

  void update(const Time&, double period) override {
    const size_t n = joints_.size();
    for (size_t k = 0; k < n; ++k)
      if (chained_mode() && std::isfinite(refs_[k]->command)) reference_[k] = refs_[k]->command;
    // The external wrench in the base frame, about the sensor's origin.
    for (size_t k = 0; k < n; ++k) q_measured_(static_cast<unsigned>(k)) = joints_[k]->position;
    KDL::Frame sensor_pose;
    fk_->JntToCart(q_measured_, sensor_pose, sensor_segment_);
    const Eigen::Matrix3d r = eig(sensor_pose.M);
    Eigen::Matrix<double, 6, 1> w;
    if (!sensor_->present) return hold();
    const std::vector<double>& s = sensor_->values;
    w.head<3>() = r * Eigen::Vector3d(s[0], s[1], s[2]);
    w.tail<3>() = r * Eigen::Vector3d(s[3], s[4], s[5]);
    const Eigen::Vector3d weight(0, 0, -weight_);
    w.head<3>() -= weight;
    w.tail<3>() -= (r * cog_).cross(weight);
    wrench_ = filtered_ ? Eigen::Matrix<double, 6, 1>((1 - filter_) * wrench_ + filter_ * w) : w;
    filtered_ = true;
    // M a + D v + K x = F on each selected axis, semi-implicit Euler.
    for (int i = 0; i < 6; ++i) {
      if (!selected_[size_t(i)]) {
        x_(i) = v_(i) = 0;
        continue;
      }
      const double a = (wrench_(i) - damping_[size_t(i)] * v_(i) - stiffness_[size_t(i)] * x_(i)) / mass_[size_t(i)];
      v_(i) += a * period;
      x_(i) += v_(i) * period;
    }
    // The tip's pose at the references, displaced by x; joint positions that reach it (damped least squares).
    for (size_t k = 0; k < n; ++k) q_(static_cast<unsigned>(k)) = reference_[k];
    KDL::Frame goal;
    fk_->JntToCart(q_, goal);
    goal.p += KDL::Vector(x_(0), x_(1), x_(2));
    if (const double angle = x_.tail<3>().norm(); angle > 0)
      goal.M = KDL::Rotation::Rot(KDL::Vector(x_(3), x_(4), x_(5)), angle) * goal.M;
    for (int it = 0; it < 5; ++it) {
      KDL::Frame at;
      fk_->JntToCart(q_, at);
      const KDL::Twist e = KDL::diff(at, goal);
      Eigen::Matrix<double, 6, 1> err;
      err << e.vel.x(), e.vel.y(), e.vel.z(), e.rot.x(), e.rot.y(), e.rot.z();
      // A rotation not selected is free: its row leaves the least squares (a 3-joint arm cannot hold its tool's
      // orientation and move it too).
      for (int i = 3; i < 6; ++i)
        if (!selected_[size_t(i)]) err(i) = 0;
      if (err.norm() < 1e-9) break;
      jac_solver_->JntToJac(q_, jac_);
      j_ = jac_.data;
      for (int i = 3; i < 6; ++i)
        if (!selected_[size_t(i)]) j_.row(i).setZero();
      const auto& j = j_;
      Eigen::Matrix<double, 6, 6> jjt = j * j.transpose();
      jjt.diagonal().array() += lambda_ * lambda_;
      const Eigen::Matrix<double, 6, 1> y = jjt.ldlt().solve(err);
      for (size_t k = 0; k < n; ++k) q_(static_cast<unsigned>(k)) += j.col(Eigen::Index(k)).dot(y);
    }
    for (size_t k = 0; k < n; ++k) joints_[k]->command = q_(static_cast<unsigned>(k));
  }

 private:
  void hold() {
    for (size_t k = 0; k < joints_.size(); ++k) joints_[k]->command = reference_[k];
  }

  std::vector<std::string> names_;
  std::vector<JointData*> joints_, refs_;
  std::vector<double> reference_;
  const SensorData* sensor_ = nullptr;
  KDL::Chain chain_;
  std::unique_ptr<KDL::ChainFkSolverPos_recursive> fk_;
  std::unique_ptr<KDL::ChainJntToJacSolver> jac_solver_;
  KDL::JntArray q_, q_measured_;
  KDL::Jacobian jac_;
  Eigen::Matrix<double, 6, Eigen::Dynamic> j_;  // jac_ with the free rotations' rows zeroed
  int sensor_segment_ = 0;  // the chain's segments up to the sensor's frame
  double lambda_ = 0.0005, filter_ = 1.0, weight_ = 0;
  Eigen::Vector3d cog_ = Eigen::Vector3d::Zero();
  std::array<bool, 6> selected_{};
  std::array<double, 6> mass_{}, damping_{}, stiffness_{};
  Eigen::Matrix<double, 6, 1> x_ = Eigen::Matrix<double, 6, 1>::Zero(), v_ = x_, wrench_ = x_;
  bool filtered_ = false;
};

}  // namespace

ControllerType admittance_controller() {
  ControllerTypeInfo t;
  t.name = "admittance_controller/AdmittanceController";
  t.ros = RosVersion::Ros2;
  t.chainable = true;
  t.references = "<name>/<joint> for each of joints, on chainable_command_interfaces (position, velocity)";
  t.doc = "the tool yields to a force-torque sensor as a mass-spring-damper per selected axis around the pose its "
          "joint references give; chainable (a JTC's command_joints)";
  t.claims = {Interface::Position, {"joints"}, "", {}};
  t.command = {"float64_array_t", "command", CommandInfo::kOnePerJoint, "position"};
  t.parameters = {
      ros2_parameter("joints", "strings", "", "the moving joints from kinematics.base to kinematics.tip, in order"),
      ros2_parameter("command_interfaces", "strings", "[position]", "[position]"),
      ros2_parameter("state_interfaces", "strings", "[position, velocity]", "read: the joints' position"),
      ros2_parameter("chainable_command_interfaces", "strings", "[position, velocity]",
                     "its reference interfaces <name>/<joint> (position written; velocity accepted)"),
      ros2_parameter("kinematics", "map", "",
                     "{base, tip, alpha (damping of the least squares), plugin_name}: KDL over the URDF"),
      ros2_parameter("ft_sensor", "map", "", "{name, filter_coefficient (1: none), frame}: the wrist sensor"),
      ros2_parameter("control", "map", "", "{frame: {id}}: read; the admittance runs in kinematics.base"),
      ros2_parameter("fixed_world_frame", "map", "", "{frame: {id}}: read; gravity is -z of kinematics.base"),
      ros2_parameter("gravity_compensation", "map", "", "{frame: {id}, CoG: {pos [m, sensor frame], force [N]}}"),
      ros2_parameter("admittance", "map", "",
                     "{selected_axes, mass [kg], damping_ratio, stiffness [N/m, N*m/rad]}, 6 each (x y z rx ry rz)"),
  };
  return {t, [](const std::string&) { return std::make_unique<AdmittanceController>(); }};
}

}  // namespace lcm_control::cm
