#include "tools/model_report.hpp"

#include <fmt/format.h>

#include <iterator>

namespace lcm_control {

std::string describe(const RobotModel& m) {
  std::string s;
  auto out = std::back_inserter(s);
  fmt::format_to(out, "robot '{}' from {}\n", m.name, m.urdf_path);
  if (!m.config_path.empty())
    fmt::format_to(out, "config from {}{}\n", m.config_path,
                   m.config_section.empty() ? "" : fmt::format(" (under '{}:')", m.config_section));
  if (!m.ns.empty()) fmt::format_to(out, "namespace: {} (channels are {}/...)\n", m.ns, m.ns);
  fmt::format_to(out, "root link: {}\n\nlinks ({}):\n", m.root_link, m.links.size());
  for (const auto& l : m.links) {
    fmt::format_to(out, "  {:<16}", l.name);
    if (l.inertial) {
      const auto& in = *l.inertial;
      const auto& p = in.origin.translation();
      fmt::format_to(out, " mass {:g} kg, com ({:g}, {:g}, {:g}), ixx {:g} iyy {:g} izz {:g} ixy {:g} ixz {:g} iyz {:g}",
                     in.mass, p.x(), p.y(), p.z(), in.inertia(0, 0), in.inertia(1, 1), in.inertia(2, 2),
                     in.inertia(0, 1), in.inertia(0, 2), in.inertia(1, 2));
    } else {
      fmt::format_to(out, " no inertial");
    }
    fmt::format_to(out, ", {} collision, {} visual\n", l.collisions.size(), l.visuals.size());
  }
  fmt::format_to(out, "\njoints ({}){}:\n", m.joints.size(), m.self_collide ? ", self_collide: links collide with each other" : "");
  for (const auto& j : m.joints) {
    const auto& o = j.origin.translation();
    fmt::format_to(out, "  {:<16} {:<10} {} -> {}, origin ({:g}, {:g}, {:g})", j.name, to_string(j.type), j.parent_link,
                   j.child_link, o.x(), o.y(), o.z());
    if (j.type != JointType::Fixed) {
      fmt::format_to(out, ", axis ({:g}, {:g}, {:g})", j.axis.x(), j.axis.y(), j.axis.z());
      if (j.has_position_limits) fmt::format_to(out, ", limits [{:g}, {:g}]", j.lower, j.upper);
      fmt::format_to(out, ", effort {:g}, velocity {:g}, damping {:g}, friction {:g}", j.effort_limit, j.velocity_limit,
                     j.damping, j.friction);
      if (j.mimic)
        fmt::format_to(out, "; mimics {} (x {:g}, offset {:g}: a gear in the simulation)", j.mimic->joint,
                       j.mimic->multiplier, j.mimic->offset);
    }
    fmt::format_to(out, "\n");
  }
  fmt::format_to(out, "\ntransmissions ({}), in actuator order:\n", m.transmissions.size());
  for (const auto& t : m.transmissions) {
    fmt::format_to(out, "  {:<8} joint {:<10} actuator {:<10} {:<24} reduction {:g}, offset {:g}", t.name, t.joint,
                   t.actuator, to_string(t.interfaces.front()), t.map.reduction, t.map.offset);
    auto g = m.pid_gains.find(t.joint);
    const Interface i = t.interfaces.front();
    if (i == Interface::Effort)
      fmt::format_to(out, "  -> effort passed through\n");
    else if (g != m.pid_gains.end())
      fmt::format_to(out, "  -> {} PID p {:g} i {:g} d {:g} i_clamp [{:g}, {:g}]{}\n",
                     i == Interface::Position ? "position" : "velocity", g->second.p, g->second.i, g->second.d,
                     g->second.i_clamp_min, g->second.i_clamp_max, g->second.antiwindup ? " antiwindup" : "");
    else
      fmt::format_to(out, "  -> {} direct (no pid_gains)\n",
                     i == Interface::Position ? "position set kinematically" : "velocity motor");
  }
  fmt::format_to(out, "gazebo_ros_control plugin tag: {}{}\n", m.has_gazebo_ros_control_plugin ? "yes" : "no",
                 m.gazebo_plugin_namespace.empty() ? "" : ", robotNamespace " + m.gazebo_plugin_namespace);
  fmt::format_to(out, "\ncontrollers ({}):\n", m.controllers.size());
  for (const auto& c : m.controllers) fmt::format_to(out, "  {:<24} {}\n", c.name, c.type);
  if (!m.warnings.empty()) {
    fmt::format_to(out, "\nwarnings ({}):\n", m.warnings.size());
    for (const auto& w : m.warnings) fmt::format_to(out, "  {}\n", w);
  }
  if (!m.hints.empty()) {
    fmt::format_to(out, "\nhints ({}):\n", m.hints.size());
    for (const auto& h : m.hints) fmt::format_to(out, "  {}\n", h);
  }
  return s;
}


}  // namespace lcm_control
