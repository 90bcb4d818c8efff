#include "description/model_check.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <set>

namespace lcm_control {

namespace {

// Limits within this of 2*pi apart are one full turn (URDFs write pi as 3.14, 3.1416 or M_PI).
constexpr double kFullTurnTolerance = 0.01;

std::string names_of(const std::vector<Joint>& joints, bool moving_only) {
  std::vector<std::string> n;
  for (const auto& j : joints)
    if (!moving_only || j.type != JointType::Fixed) n.push_back(j.name);
  return n.empty() ? "none" : fmt::format("{}", fmt::join(n, ", "));
}

// True when a moving joint hangs below `j`. A last joint with one-turn limits (a turret, a rotor, a wheel) is
// often meant to turn without end; an inner one (an elbow at +-pi) usually has a real stop.
bool moves_anything_below(const RobotModel& model, const Joint& j) {
  std::vector<std::string> frontier{j.child_link};
  for (size_t guard = 0; !frontier.empty() && guard < model.joints.size(); ++guard) {
    std::vector<std::string> next;
    for (const auto& link : frontier)
      for (const auto& c : model.joints)
        if (c.parent_link == link) {
          if (c.type != JointType::Fixed) return true;
          next.push_back(c.child_link);
        }
    frontier = std::move(next);
  }
  return false;
}

// True when the hardware only ever sets the joint's position (every interface it takes is position, with no
// pid_gains): gazebo_ros_control then moves it kinematically and never reads its effort limit.
bool sets_position_directly(const RobotModel& model, const std::string& joint) {
  const TransmissionSpec* t = model.transmission_for_joint(joint);
  if (!t || t->interfaces.empty() || model.pid_gains.count(joint)) return false;
  const size_t offered = t->any_interface ? t->interfaces.size() : 1;
  for (size_t k = 0; k < offered; ++k)
    if (t->interfaces[k] != Interface::Position) return false;
  return true;
}

// The YAML key path of a joint's pid_gains.
std::string gains_key(const RobotModel& model, const std::string& joint) {
  return (model.config_section.empty() ? "" : model.config_section + "/") + "gazebo_ros_control/pid_gains/" + joint;
}

// Largest magnitudes taken (SI units): beyond them, or not finite, a value is a typo or a corrupted file, and
// Bullet would turn it into non-finite states.
constexpr double kMaxLength = 1e4;     // m: origins, collision sizes
constexpr double kMaxMass = 1e6;       // kg
constexpr double kMaxInertia = 1e6;    // kg m^2
constexpr double kMaxLimit = 1e6;      // rad or m: position limits
constexpr double kMaxVelocity = 1e6;   // rad/s or m/s
constexpr double kMaxEffort = 1e9;     // N m or N; also damping and friction

// Appends "<what> is <v>, ..." when v is not finite or larger than max in magnitude.
void check_number(std::vector<std::string>& problems, const std::string& where, const char* what, double v,
                  double max) {
  if (std::isfinite(v) && std::abs(v) <= max) return;
  problems.push_back(fmt::format("{}: {} is {}; every number must be finite and at most {:g} in magnitude here "
                                 "(SI units): fix the value",
                                 where, what, v, max));
}

void check_pose(std::vector<std::string>& problems, const std::string& where, const char* what,
                const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d t = pose.translation();
  for (int k = 0; k < 3; ++k) check_number(problems, where, what, t[k], kMaxLength);
  if (!pose.linear().allFinite())
    problems.push_back(fmt::format("{}: {} has a non-finite rpy; fix the value", where, what));
}

void check_numbers(const RobotModel& model, std::vector<std::string>& problems) {
  const std::string& u = model.urdf_path;
  for (const auto& l : model.links) {
    const std::string where = fmt::format("{}: link '{}'", u, l.name);
    if (l.inertial) {
      check_number(problems, where, "<mass value>", l.inertial->mass, kMaxMass);
      check_pose(problems, where, "<inertial><origin>", l.inertial->origin);
      for (int r = 0; r < 3; ++r)
        for (int k = r; k < 3; ++k) check_number(problems, where, "an <inertia> entry", l.inertial->inertia(r, k), kMaxInertia);
    }
    for (const auto& g : l.collisions) {
      check_pose(problems, where, "<collision><origin>", g.origin);
      for (int k = 0; k < 3; ++k) {
        check_number(problems, where, "a <box size>", g.size[k], kMaxLength);
        check_number(problems, where, "a <mesh scale>", g.scale[k], kMaxLength);
      }
      check_number(problems, where, "a collision radius", g.radius, kMaxLength);
      check_number(problems, where, "a collision length", g.length, kMaxLength);
    }
  }
  for (const auto& j : model.joints) {
    const std::string where = fmt::format("{}: joint '{}'", u, j.name);
    check_pose(problems, where, "<origin>", j.origin);
    if (!j.axis.allFinite()) problems.push_back(fmt::format("{}: <axis> is not finite; fix the value", where));
    if (j.type == JointType::Fixed) continue;
    if (j.has_position_limits) {
      check_number(problems, where, "<limit lower>", j.lower, kMaxLimit);
      check_number(problems, where, "<limit upper>", j.upper, kMaxLimit);
    }
    // No <limit> (a continuous joint) reads as infinite effort and velocity: no limit, which is fine.
    if (j.effort_limit != HUGE_VAL) check_number(problems, where, "<limit effort>", j.effort_limit, kMaxEffort);
    if (j.velocity_limit != HUGE_VAL) check_number(problems, where, "<limit velocity>", j.velocity_limit, kMaxVelocity);
    check_number(problems, where, "<dynamics damping>", j.damping, kMaxEffort);
    check_number(problems, where, "<dynamics friction>", j.friction, kMaxEffort);
  }
}

}  // namespace

void check_model(RobotModel& model, std::vector<std::string>& problems) {
  const std::string& u = model.urdf_path;
  const std::string& c = model.config_path;
  check_numbers(model, problems);

  for (const auto& j : model.joints) {
    if (j.type == JointType::Fixed) continue;
    if (j.type == JointType::Floating || j.type == JointType::Planar) {
      problems.push_back(fmt::format("{}: joint '{}' is {}; only revolute, continuous, prismatic and fixed joints are "
                                     "supported",
                                     u, j.name, to_string(j.type)));
      continue;
    }
    if (j.axis.norm() == 0) problems.push_back(fmt::format("{}: joint '{}': <axis> is zero", u, j.name));
    if (j.has_position_limits) {
      if (!(j.lower < j.upper))
        problems.push_back(fmt::format("{}: joint '{}': limit lower {} >= upper {}; the joint could not move (use a "
                                       "continuous joint for no limits)",
                                       u, j.name, j.lower, j.upper));
      else if (j.type == JointType::Revolute && std::abs(j.upper - j.lower - 2 * M_PI) < kFullTurnTolerance &&
               !moves_anything_below(model, j))
        model.hints.push_back(fmt::format("{}: joint '{}': limits [{:g}, {:g}] span one full turn; the position stops at "
                                          "the limits and does not wrap, so a joint meant to turn without end should be "
                                          "<joint type=\"continuous\">",
                                          u, j.name, j.lower, j.upper));
    }
    // No actuator (no transmission, no <ros2_control> command interface): the joint is passive, free or sprung as in
    // Gazebo, and its <limit effort velocity> (often both 0) describe an actuator it does not have.
    if (!model.transmission_for_joint(j.name)) {
      if (!j.mimic && (j.effort_limit == 0 || j.velocity_limit == 0))
        model.notes.push_back(fmt::format("{}: joint '{}' is passive (nothing drives it): it moves freely{}, and its "
                                          "<limit{}{}> applies to no actuator",
                                          u, j.name, j.spring ? " on its spring" : "",
                                          j.effort_limit == 0 ? " effort=\"0\"" : "",
                                          j.velocity_limit == 0 ? " velocity=\"0\"" : ""));
    } else if (j.effort_limit == 0 && sets_position_directly(model, j.name))
      model.warnings.push_back(fmt::format("{}: joint '{}': <limit effort=\"0\"> ignored: the joint takes position "
                                           "commands without pid_gains, so it is moved directly and no effort limit "
                                           "applies (as in Gazebo)",
                                           u, j.name));
    else if (j.effort_limit == 0)
      problems.push_back(fmt::format("{}: joint '{}': <limit effort=\"0\"> would freeze the joint (no force allowed{}); "
                                     "set the actuator's real effort limit",
                                     u, j.name,
                                     model.pid_gains.count(j.name) ? fmt::format(": its pid_gains in {} drive it by effort",
                                                                                 model.config_file_of(gains_key(model, j.name)))
                                                                   : ""));
    if (j.velocity_limit == 0 && model.transmission_for_joint(j.name))
      problems.push_back(fmt::format("{}: joint '{}': <limit velocity=\"0\"> would freeze the joint; set the real "
                                     "velocity limit",
                                     u, j.name));
    if (j.effort_limit < 0 || j.velocity_limit < 0)
      problems.push_back(fmt::format("{}: joint '{}': effort and velocity limits must be positive", u, j.name));
    if (j.damping < 0 || j.friction < 0)
      problems.push_back(fmt::format("{}: joint '{}': damping and friction must be >= 0", u, j.name));
  }
  for (Joint& j : model.joints) {
    if (!j.mimic) continue;
    if (const TransmissionSpec* t = model.transmission_for_joint(j.name)) {
      model.warnings.push_back(fmt::format(
          "{}: joint '{}' mimics '{}' but transmission '{}' drives it: it is driven by its transmission, as in Gazebo, "
          "and the <mimic> is ignored (remove the transmission to couple it to '{}')",
          u, j.name, j.mimic->joint, t->name, j.mimic->joint));
      j.mimic.reset();
      continue;
    }
    const Joint* leader = model.joint(j.mimic->joint);
    const std::string what = fmt::format("{}: joint '{}' <mimic joint=\"{}\">", u, j.name, j.mimic->joint);
    if (j.type == JointType::Fixed)
      problems.push_back(what + ": a fixed joint cannot mimic; remove the <mimic> or make it move");
    else if (!leader)
      problems.push_back(fmt::format("{}: there is no joint '{}' (moving joints: {})", what, j.mimic->joint,
                                     names_of(model.joints, true)));
    else if (leader == &j)
      problems.push_back(what + ": a joint cannot mimic itself");
    else if (leader->type == JointType::Fixed)
      problems.push_back(what + ": that joint is fixed; mimic a moving joint");
    else if (leader->mimic)
      problems.push_back(fmt::format("{}: '{}' mimics '{}' itself; mimic '{}' directly (multiply the multipliers)",
                                     what, leader->name, leader->mimic->joint, leader->mimic->joint));
    else if ((leader->type == JointType::Prismatic) != (j.type == JointType::Prismatic))
      problems.push_back(what + ": one is prismatic and the other is not; a mimic couples two revolute or two "
                                "prismatic joints");
  }
  for (const auto& l : model.links)
    if (l.inertial && l.inertial->mass < 0)
      problems.push_back(fmt::format("{}: link '{}': negative mass {}", u, l.name, l.inertial->mass));

  std::set<std::string> seen_actuators;
  for (const auto& t : model.transmissions) {
    const Joint* j = model.joint(t.joint);
    if (!j) {
      problems.push_back(fmt::format("{}: transmission '{}' names joint '{}', which is not in the URDF (moving joints: {})",
                                     u, t.name, t.joint, names_of(model.joints, true)));
      continue;
    }
    if (j->type == JointType::Fixed)
      problems.push_back(fmt::format("{}: transmission '{}': joint '{}' is fixed and cannot be actuated", u, t.name, t.joint));
    if (!seen_actuators.insert(t.actuator).second)
      problems.push_back(fmt::format("{}: actuator name '{}' is used by transmissions of two joints; give each its own "
                                     "<actuator name>",
                                     u, t.actuator));
  }

  for (const auto& [joint, gains] : model.pid_gains) {
    const Joint* j = model.joint(joint);
    const TransmissionSpec* t = model.transmission_for_joint(joint);
    const std::string gains_file = model.config_file_of(gains_key(model, joint));
    if (!j) {
      problems.push_back(fmt::format("{}: gazebo_ros_control/pid_gains/{}: joint '{}' is not in the URDF {} (moving "
                                     "joints: {})",
                                     gains_file, joint, joint, u, names_of(model.joints, true)));
    } else if (!t) {
      model.warnings.push_back(fmt::format("{}: gazebo_ros_control/pid_gains/{}: joint has no transmission in {}, so the "
                                           "gains are not used",
                                           gains_file, joint, u));
    } else if (t->interfaces.front() == Interface::Effort) {
      model.warnings.push_back(fmt::format("{}: gazebo_ros_control/pid_gains/{}: the joint takes effort commands, so "
                                           "the gains are not used",
                                           gains_file, joint));
    }
    (void)gains;
  }
  std::set<std::string> names;
  for (const auto& ctl : model.controllers)
    if (!names.insert(ctl.name).second)
      problems.push_back(fmt::format("{}: controller '{}' is defined twice", c, ctl.name));
  if (!model.transmissions.empty() && !model.has_gazebo_ros_control_plugin && model.ros2_control.empty())
    model.warnings.push_back(fmt::format("{}: no <gazebo><plugin filename=\"libgazebo_ros_control.so\"/>; not needed "
                                         "here, but ROS would not start ros_control without it",
                                         u));
}


void validate(RobotModel& model) {
  std::vector<std::string> problems;
  check_model(model, problems);
  if (!problems.empty()) throw ModelError(problems);
}

std::string simulation_size_problem(const RobotModel& model) {
  size_t moving = 0;
  for (const Joint& j : model.joints) moving += j.type != JointType::Fixed;
  const size_t all = model.joints.size();
  if (all <= kMaxSimulatedJoints) return "";
  return fmt::format("{}: {} joints ({} moving, {} fixed): sim_server simulates at most {} (every joint, a fixed one "
                     "too, is a link of Bullet's multibody, whose start-up time and memory grow with the square of "
                     "the links: 1,000 take about 4 s and 200 MB); merge links that need no joint of their own, split "
                     "the robot, or run it on mock hardware (--mock-hardware)",
                     model.urdf_path, all, moving, all - moving, kMaxSimulatedJoints);
}

}  // namespace lcm_control
