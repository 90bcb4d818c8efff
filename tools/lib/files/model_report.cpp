#include "tools/lib/files/model_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <iterator>

namespace lcm_control {

namespace {

std::string interfaces(const std::vector<Ros2Interface>& v) {
  std::vector<std::string> items;
  for (const auto& i : v) {
    std::vector<std::string> extra;
    if (!i.data_type.empty()) extra.push_back(i.data_type);
    if (i.min) extra.push_back(fmt::format("min {:g}", *i.min));
    if (i.max) extra.push_back(fmt::format("max {:g}", *i.max));
    if (i.initial_value) extra.push_back(fmt::format("initial_value {:g}", *i.initial_value));
    items.push_back(extra.empty() ? i.name : fmt::format("{} ({})", i.name, fmt::join(extra, ", ")));
  }
  return fmt::format("[{}]", fmt::join(items, ", "));
}

// The <ros2_control> blocks: hardware, per-joint interfaces, sensors and gpios, the start pose, the plugin tag.
void describe_ros2_control(const RobotModel& m, std::string& s) {
  auto out = std::back_inserter(s);
  fmt::format_to(out, "\nros2_control hardware ({}):\n", m.ros2_control.size());
  for (const HardwareBlock& b : m.ros2_control) {
    fmt::format_to(out, "  {} ({}): {} -> {}\n", b.name, b.type.empty() ? "system" : b.type, b.plugin,
                   b.kind == HardwareKind::Mock ? "mock hardware" : "simulated");
    for (const auto& [k, v] : b.params) fmt::format_to(out, "    param {} = {}\n", k, v);
    for (const Ros2Component& c : b.joints) {
      fmt::format_to(out, "    joint {:<20}", c.name);
      const Joint* j = m.joint(c.name);
      if (c.mimic && j && j->mimic)
        fmt::format_to(out, " mimics {} (x {:g}, offset {:g});", j->mimic->joint, j->mimic->multiplier,
                       j->mimic->offset);
      else if (c.command_interfaces.empty())
        fmt::format_to(out, " not actuated;");
      if (!c.command_interfaces.empty()) fmt::format_to(out, " command {}", interfaces(c.command_interfaces));
      fmt::format_to(out, " state {}\n", interfaces(c.state_interfaces));
    }
    for (const Ros2Component& c : b.sensors)
      fmt::format_to(out, "    sensor {:<19} state {} (see sensors below)\n", c.name, interfaces(c.state_interfaces));
    for (const Ros2Component& c : b.gpios)
      fmt::format_to(out, "    gpio {:<21} command {} state {} (read, not simulated yet)\n", c.name,
                     interfaces(c.command_interfaces), interfaces(c.state_interfaces));
    for (const Ros2Transmission& t : b.transmissions)
      fmt::format_to(out, "    transmission {}: joint {}, actuator {}, reduction {:g}, offset {:g}\n", t.name, t.joint,
                     t.actuator, t.reduction, t.offset);
  }
  if (!m.initial_positions.empty() || !m.initial_velocities.empty()) {
    std::vector<std::string> p;
    for (const Joint& j : m.joints) {
      const auto q = m.initial_positions.find(j.name);
      const auto v = m.initial_velocities.find(j.name);
      if (q != m.initial_positions.end()) p.push_back(fmt::format("{} {:g}", j.name, q->second));
      if (v != m.initial_velocities.end() && v->second != 0)
        p.push_back(fmt::format("{} velocity {:g}", j.name, v->second));
    }
    fmt::format_to(out, "start pose (initial_value): {}\n", fmt::join(p, ", "));
  }
  const Ros2ControlPlugin& g = m.ros2_control_plugin;
  if (g.present)
    fmt::format_to(out, "gz_ros2_control plugin tag: {}{}{}{}\n", g.filename,
                   g.parameters.empty() ? "" : fmt::format(", parameters {}", fmt::join(g.parameters, ", ")),
                   g.ns.empty() ? "" : ", namespace " + g.ns,
                   g.hold_joints ? "" : ", hold_joints false (joints nobody commands are not braked)");
  else
    fmt::format_to(out, "gz_ros2_control plugin tag: no\n");
}

std::string noise_text(const char* what, const AxisNoise& n) {
  if (!n[0].any() && !n[1].any() && !n[2].any()) return "";
  std::vector<std::string> axes;
  for (const GaussianNoise& g : n) {
    std::string a = fmt::format("{:g}", g.stddev);
    if (g.mean != 0) a += fmt::format(" mean {:g}", g.mean);
    if (g.bias_mean != 0 || g.bias_stddev != 0) a += fmt::format(" bias {:g}/{:g}", g.bias_mean, g.bias_stddev);
    axes.push_back(a);
  }
  return fmt::format(", {} noise sd ({})", what, fmt::join(axes, ", "));
}

// Every declared sensor: kind, where it sits, its frame, its noise, or why it is not simulated.
void describe_sensors(const RobotModel& m, std::string& s) {
  if (m.sensors.empty()) return;
  auto out = std::back_inserter(s);
  size_t simulated = 0;
  for (const SensorSpec& x : m.sensors) simulated += x.simulated();
  fmt::format_to(out, "\nsensors ({}, {} simulated):\n", m.sensors.size(), simulated);
  for (const SensorSpec& x : m.sensors) {
    fmt::format_to(out, "  {:<20} {:<12}", x.name.empty() ? "(unnamed)" : x.name, x.type);
    if (!x.simulated()) {
      fmt::format_to(out, " NOT simulated: {}\n", x.not_simulated);
      continue;
    }
    if (x.kind == SensorKind::ForceTorque)
      fmt::format_to(out, " joint {} (child {}), wrench in the {} frame, {}", x.joint, x.link,
                     x.frame == WrenchFrame::Child ? "child" : x.frame == WrenchFrame::Parent ? "parent" : "sensor",
                     x.direction == MeasureDirection::ChildToParent ? "child_to_parent" : "parent_to_child");
    else
      fmt::format_to(out, " link {}", x.link);
    const auto& p = x.pose.translation();
    if (!x.pose.isApprox(Eigen::Isometry3d::Identity()))
      fmt::format_to(out, ", pose ({:g}, {:g}, {:g}){}", p.x(), p.y(), p.z(),
                     x.pose.linear().isApprox(Eigen::Matrix3d::Identity()) ? "" : " rotated");
    fmt::format_to(out, ", frame_id {}", x.frame_id.empty() ? x.link : x.frame_id);
    s += noise_text("angular_velocity", x.angular_velocity) + noise_text("linear_acceleration", x.linear_acceleration) +
         noise_text("force", x.force) + noise_text("torque", x.torque);
    if (!x.hardware_block.empty()) fmt::format_to(out, ", in ros2_control '{}'", x.hardware_block);
    if (x.update_rate_hz > 0) fmt::format_to(out, " (declared {:g} Hz; measured every step)", x.update_rate_hz);
    fmt::format_to(out, "\n");
  }
}

}  // namespace

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
    if (t.any_interface && t.interfaces.size() > 1) {
      std::vector<std::string> others;
      for (size_t k = 1; k < t.interfaces.size(); ++k) others.push_back(to_string(t.interfaces[k]));
      fmt::format_to(out, "           switches at run time to {} when a controller claims it\n", fmt::join(others, " or "));
    }
  }
  if (m.ros2_control.empty())
    fmt::format_to(out, "gazebo_ros_control plugin tag: {}{}\n", m.has_gazebo_ros_control_plugin ? "yes" : "no",
                   m.gazebo_plugin_namespace.empty() ? "" : ", robotNamespace " + m.gazebo_plugin_namespace);
  else
    describe_ros2_control(m, s);
  describe_sensors(m, s);
  if (m.update_rate_hz) fmt::format_to(out, "\nupdate_rate: {:g} Hz (controller_manager)\n", *m.update_rate_hz);
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
