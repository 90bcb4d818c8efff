#include "description/urdf_reader.hpp"

#include <console_bridge/console.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>

#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <set>
#include <sstream>

#include "description/robot_file.hpp"
#include "description/packages.hpp"
#include "description/text.hpp"

namespace fs = std::filesystem;

namespace lcm_control {

namespace {

// Meshes the URDF names but that are not there, reported once per missing package (a whole package off the
// path is one mistake with one fix) and once per other file.
struct MissingMeshes {
  std::string kind, urdf, base_dir;
  const std::vector<std::string>& package_path;
  std::map<std::string, std::vector<std::string>> by_package;  // package -> "link 'L' (uri)"
  std::vector<std::string> files;

  void add(const std::string& link, const std::string& uri) {
    const std::string where = fmt::format("link '{}' ({})", link, uri);
    const std::string prefix = "package://";
    if (uri.rfind(prefix, 0) == 0) {
      const std::string pkg = uri.substr(prefix.size(), uri.find('/', prefix.size()) - prefix.size());
      if (find_package_dir(pkg, package_path).empty()) {
        by_package[pkg].push_back(where);
        return;
      }
    }
    files.push_back(where);
  }

  void report(std::vector<std::string>& out) const {
    const std::string searched = package_path.empty() ? "empty" : fmt::format("{}", fmt::join(package_path, ":"));
    for (const auto& [pkg, uses] : by_package)
      out.push_back(fmt::format("{}: package '{}' of {} {} mesh{} not found (first: {}); give --package-path DIR "
                                "with DIR the folder holding {}/ (or set LCM_CONTROL_PACKAGE_PATH or "
                                "ROS_PACKAGE_PATH); searched: {}",
                                urdf, pkg, uses.size(), kind, uses.size() == 1 ? "" : "es", uses.front(), pkg,
                                searched));
    for (const auto& f : files)
      out.push_back(fmt::format("{}: {}: {} mesh not found (relative paths are read from {}; package:// in "
                                "--package-path / LCM_CONTROL_PACKAGE_PATH / ROS_PACKAGE_PATH: {})",
                                urdf, f, kind, base_dir, searched));
  }
};

// urdfdom reports through console_bridge; keep the messages for our own one-line error.
class CaptureHandler : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_WARN) messages.push_back(trim(text));
  }
  std::vector<std::string> messages;
};

Eigen::Isometry3d to_iso(const urdf::Pose& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() << p.position.x, p.position.y, p.position.z;
  t.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).normalized().toRotationMatrix();
  return t;
}

Geometry to_geometry(const urdf::GeometrySharedPtr& g, const urdf::Pose& origin, const std::string& base_dir,
                     const std::vector<std::string>& package_path) {
  Geometry out;
  out.origin = to_iso(origin);
  switch (g->type) {
    case urdf::Geometry::BOX: {
      auto b = std::static_pointer_cast<urdf::Box>(g);
      out.type = Geometry::Type::Box;
      out.size << b->dim.x, b->dim.y, b->dim.z;
      break;
    }
    case urdf::Geometry::CYLINDER: {
      auto c = std::static_pointer_cast<urdf::Cylinder>(g);
      out.type = Geometry::Type::Cylinder;
      out.radius = c->radius;
      out.length = c->length;
      break;
    }
    case urdf::Geometry::SPHERE: {
      auto s = std::static_pointer_cast<urdf::Sphere>(g);
      out.type = Geometry::Type::Sphere;
      out.radius = s->radius;
      break;
    }
    case urdf::Geometry::MESH: {
      auto m = std::static_pointer_cast<urdf::Mesh>(g);
      out.type = Geometry::Type::Mesh;
      out.mesh_uri = m->filename;
      out.scale << m->scale.x, m->scale.y, m->scale.z;
      out.mesh_path = resolve_resource(m->filename, base_dir, package_path);
      break;
    }
  }
  return out;
}

JointType to_joint_type(int t) {
  switch (t) {
    case urdf::Joint::REVOLUTE: return JointType::Revolute;
    case urdf::Joint::CONTINUOUS: return JointType::Continuous;
    case urdf::Joint::PRISMATIC: return JointType::Prismatic;
    case urdf::Joint::FLOATING: return JointType::Floating;
    case urdf::Joint::PLANAR: return JointType::Planar;
    default: return JointType::Fixed;
  }
}

const char* child_text(const tinyxml2::XMLElement* e, const char* name) {
  const tinyxml2::XMLElement* c = e ? e->FirstChildElement(name) : nullptr;
  return c && c->GetText() ? c->GetText() : nullptr;
}


const char* kInterfaceNames[] = {"PositionJointInterface", "VelocityJointInterface", "EffortJointInterface"};
// hardware_interface's other interfaces: real, but not commands this hardware takes.
const char* kOtherRosInterfaces[] = {"JointStateInterface",       "PosVelJointInterface",     "PosVelAccJointInterface",
                                     "JointModeInterface",        "ActuatorStateInterface",   "PositionActuatorInterface",
                                     "VelocityActuatorInterface", "EffortActuatorInterface",  "ImuSensorInterface",
                                     "ForceTorqueSensorInterface"};

// One <hardwareInterface> text: a command interface, or why not. An unknown name in hardware_interface is a
// typo (an error, as gazebo_ros_control refuses it); a known one we do not command, or another package's
// (franka_hw/...), is skipped.
struct InterfaceRead {
  std::optional<Interface> iface;
  bool typo = false;
  std::string suggestion;
};
InterfaceRead read_interface(const std::string& text) {
  InterfaceRead r;
  r.iface = parse_interface(text);
  if (r.iface) return r;
  std::string bare = text;
  const std::string prefix = "hardware_interface/";
  if (bare.rfind(prefix, 0) == 0) bare = bare.substr(prefix.size());
  if (bare.find('/') != std::string::npos) return r;  // another package's interface
  for (const char* known : kOtherRosInterfaces)
    if (bare == known) return r;
  r.typo = true;
  r.suggestion = closest_name(bare, {std::begin(kInterfaceNames), std::end(kInterfaceNames)}, 8);
  return r;
}

// A transmission that can drive a joint, with where it was written.
struct Candidate {
  TransmissionSpec spec;
  int line = 0;
  bool no_reduction = false;  // no <mechanicalReduction>: 1 is used
};

// Reads one <transmission>; returns false (with a warning or a problem) when it cannot be used.
bool read_transmission(RobotModel& model, const tinyxml2::XMLElement* t, const std::string& file, Candidate& out,
                       std::vector<std::string>& problems) {
  TransmissionSpec& spec = out.spec;
  out.line = t->GetLineNum();
  const char* tname = t->Attribute("name");
  spec.name = tname ? tname : "";
  const std::string where = fmt::format("{}:{}: transmission '{}'", file, out.line, spec.name);
  if (spec.name.empty()) problems.push_back(fmt::format("{}: has no name attribute; add name=\"...\"", where));

  if (const char* type = child_text(t, "type")) spec.type = trim(type);
  if (spec.type.empty())
    if (const char* a = t->Attribute("type")) spec.type = trim(a);  // ROS's old-style type attribute
  if (spec.type.empty()) {
    problems.push_back(fmt::format("{}: no <type>; add <type>transmission_interface/SimpleTransmission</type>", where));
    return false;
  }
  std::vector<std::string> joints;
  for (auto* j = t->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint"))
    joints.push_back(j->Attribute("name") ? j->Attribute("name") : "");
  const std::string joint_list = joints.empty() ? "no joint" : "joint " + join(joints);
  if (spec.type != "transmission_interface/SimpleTransmission" && spec.type != "SimpleTransmission") {
    model.warnings.push_back(fmt::format("{}: skipped: type '{}' is not supported (only "
                                         "transmission_interface/SimpleTransmission is); it gives {} no interface",
                                         where, spec.type, joint_list));
    return false;
  }
  int n_actuators = 0;
  for (auto* a = t->FirstChildElement("actuator"); a; a = a->NextSiblingElement("actuator")) ++n_actuators;
  if (joints.size() != 1 || n_actuators != 1) {
    model.warnings.push_back(fmt::format("{}: skipped: a SimpleTransmission needs exactly one <joint> and one "
                                         "<actuator> (found {} and {})",
                                         where, joints.size(), n_actuators));
    return false;
  }
  auto* je = t->FirstChildElement("joint");
  spec.joint = joints.front();
  if (spec.joint.empty()) {
    problems.push_back(fmt::format("{}: <joint> has no name attribute", where));
    return false;
  }
  auto* ae = t->FirstChildElement("actuator");
  std::vector<std::string> ignored;
  auto read_interfaces = [&](const tinyxml2::XMLElement* parent) {
    for (auto* hi = parent->FirstChildElement("hardwareInterface"); hi; hi = hi->NextSiblingElement("hardwareInterface")) {
      const std::string text = trim(hi->GetText() ? hi->GetText() : "");
      const InterfaceRead r = read_interface(text);
      if (r.typo) {
        problems.push_back(fmt::format("{}: joint '{}': unknown hardwareInterface '{}'; {}use hardware_interface/"
                                       "PositionJointInterface, VelocityJointInterface or EffortJointInterface",
                                       where, spec.joint, text,
                                       r.suggestion.empty() ? "" : "did you mean " + r.suggestion + "? "));
      } else if (!r.iface) {
        ignored.push_back(text);
      } else if (std::find(spec.interfaces.begin(), spec.interfaces.end(), *r.iface) == spec.interfaces.end()) {
        spec.interfaces.push_back(*r.iface);
      }
    }
  };
  read_interfaces(je);
  if (spec.interfaces.empty() && ignored.empty()) {
    read_interfaces(ae);  // deprecated in ROS, still accepted: the interface on the actuator
    if (!spec.interfaces.empty())
      model.warnings.push_back(fmt::format("{}: hardwareInterface given on the actuator; move it into <joint name=\"{}\">",
                                           where, spec.joint));
  }
  for (const auto& p : problems)
    if (p.rfind(where, 0) == 0) return false;
  if (spec.interfaces.empty()) {
    if (ignored.empty())
      problems.push_back(fmt::format("{}: joint '{}' has no <hardwareInterface>; add hardware_interface/"
                                     "PositionJointInterface, VelocityJointInterface or EffortJointInterface",
                                     where, spec.joint));
    else
      model.warnings.push_back(fmt::format("{}: skipped: joint '{}': interface {} is not a command interface this "
                                           "hardware offers (PositionJointInterface, VelocityJointInterface, "
                                           "EffortJointInterface)",
                                           where, spec.joint, join(ignored)));
    return false;
  }
  if (!ignored.empty())
    model.warnings.push_back(fmt::format("{}: joint '{}': interface {} is not supported here; ignored", where,
                                         spec.joint, join(ignored)));
  if (spec.interfaces.size() > 1)
    model.warnings.push_back(fmt::format("{}: joint '{}' declares {} interfaces; the hardware takes the first, {}", where,
                                         spec.joint, spec.interfaces.size(), to_string(spec.interfaces.front())));
  if (const char* off = child_text(je, "offset")) {
    if (!parse_double(off, spec.map.offset))
      problems.push_back(fmt::format("{}: joint '{}': <offset> '{}' is not a number", where, spec.joint, trim(off)));
  }
  const char* an = ae->Attribute("name");
  spec.actuator = an ? an : "";
  if (spec.actuator.empty()) spec.actuator = spec.joint + "_actuator";
  if (const char* red = child_text(ae, "mechanicalReduction")) {
    if (!parse_double(red, spec.map.reduction))
      problems.push_back(fmt::format("{}: actuator '{}': <mechanicalReduction> '{}' is not a number", where,
                                     spec.actuator, trim(red)));
    else if (spec.map.reduction == 0)
      problems.push_back(fmt::format("{}: actuator '{}': <mechanicalReduction> is 0; a reduction ratio cannot be zero "
                                     "(use 1 for a direct drive, a negative value to flip the direction)",
                                     where, spec.actuator));
  } else {
    out.no_reduction = true;
  }
  return true;
}

// Every usable transmission; where a joint has several, the first in the file drives it (one warning per joint).
void parse_transmissions(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                         std::vector<std::string>& problems) {
  std::vector<Candidate> usable;
  for (auto* t = robot->FirstChildElement("transmission"); t; t = t->NextSiblingElement("transmission")) {
    Candidate c;
    if (read_transmission(model, t, file, c, problems)) usable.push_back(std::move(c));
  }
  std::map<std::string, std::vector<const Candidate*>> by_joint;
  std::vector<std::string> no_reduction;
  for (const Candidate& c : usable) by_joint[c.spec.joint].push_back(&c);
  for (const Candidate& c : usable) {
    const auto& all = by_joint[c.spec.joint];
    if (all.front() != &c) continue;
    if (all.size() > 1) {
      std::vector<std::string> others;
      for (size_t k = 1; k < all.size(); ++k)
        others.push_back(fmt::format("'{}' (line {}, {})", all[k]->spec.name, all[k]->line,
                                     to_string(all[k]->spec.interfaces.front())));
      model.warnings.push_back(fmt::format(
          "{}: joint '{}' has {} transmissions; the first, '{}' (line {}, {}), drives it and the other {} {} skipped: {}",
          file, c.spec.joint, all.size(), c.spec.name, c.line, to_string(c.spec.interfaces.front()), all.size() - 1,
          all.size() == 2 ? "is" : "are", join(others)));
    }
    model.transmissions.push_back(c.spec);
    for (size_t k = 1; k < all.size(); ++k)
      model.transmissions.back().skipped_interfaces.push_back(all[k]->spec.interfaces.front());
    if (c.no_reduction) no_reduction.push_back(c.spec.actuator);
  }
  if (!no_reduction.empty())
    model.warnings.push_back(fmt::format("{}: {} {} {} no <mechanicalReduction>; using 1 (ROS's transmission loader "
                                         "requires it)",
                                         file, no_reduction.size() == 1 ? "actuator" : "actuators", join(no_reduction),
                                         no_reduction.size() == 1 ? "has" : "have"));
}

// Plugins read by ros2_control.cpp (the gz_ros2_control tag) and sensors.cpp (ROS 1's IMU and force-torque
// plugins), and gz's sensor systems, which only switch on the sensors the URDF declares.
bool read_elsewhere(const std::string& filename) {
  for (const char* part : {"ros2_control", "gazebo_ros_imu", "gazebo_ros_ft_sensor", "gz-sim-imu-system",
                           "gz-sim-forcetorque-system", "gz-sim-contact-system", "ignition-gazebo-imu-system",
                           "ignition-gazebo-forcetorque-system", "ignition-gazebo-contact-system"})
    if (filename.find(part) != std::string::npos) return true;
  return false;
}

// A <gazebo reference> number tag: its value, or a problem naming the file, line and tag.
std::optional<double> gazebo_number(const tinyxml2::XMLElement* g, const char* tag, const std::string& file,
                                    const std::string& ref, bool non_negative, std::vector<std::string>& problems) {
  const tinyxml2::XMLElement* e = g->FirstChildElement(tag);
  if (!e) return std::nullopt;
  double v = 0;
  if (e->GetText() && parse_double(trim(e->GetText()), v) && std::isfinite(v) && (!non_negative || v >= 0)) return v;
  problems.push_back(fmt::format("{}:{}: <gazebo reference=\"{}\"><{}>{}</{}> is not {}; write a number such as 0.5",
                                 file, e->GetLineNum(), ref, tag, e->GetText() ? e->GetText() : "", tag,
                                 non_negative ? "a number >= 0" : "a finite number"));
  return std::nullopt;
}

// A link's <gazebo reference>: mu1, mu2 and fdir1 (friction), turnGravityOff.
void read_gazebo_link(RobotModel& model, Link& l, const tinyxml2::XMLElement* g, const std::string& file,
                      std::vector<std::string>& problems) {
  if (const auto mu = gazebo_number(g, "mu1", file, l.name, true, problems)) l.friction = *mu;
  if (const char* off = child_text(g, "turnGravityOff")) l.gravity_off = trim(off) == "true" || trim(off) == "1";
  const auto mu2 = gazebo_number(g, "mu2", file, l.name, true, problems);
  const tinyxml2::XMLElement* fdir = g->FirstChildElement("fdir1");
  if (!fdir) {
    if (mu2 && *mu2 != l.friction.value_or(1.0))
      model.warnings.push_back(fmt::format("{}: link '{}': <mu2>{:g}</mu2> differs from <mu1> but no <fdir1> says "
                                           "which way it acts; the contact's friction is mu1 ({:g}) every way",
                                           file, l.name, *mu2, l.friction.value_or(1.0)));
    return;
  }
  Link::FrictionDirection d;
  std::istringstream in(fdir->GetText() ? fdir->GetText() : "");
  double x = 0, y = 0, z = 0;
  std::string rest;
  if (!(in >> x >> y >> z) || (in >> rest) || !std::isfinite(x + y + z) || Eigen::Vector3d(x, y, z).norm() < 1e-9) {
    problems.push_back(fmt::format("{}:{}: link '{}': <fdir1>{}</fdir1> is not a direction; write three numbers, not "
                                   "all zero, such as 1 0 0",
                                   file, fdir->GetLineNum(), l.name, fdir->GetText() ? fdir->GetText() : ""));
    return;
  }
  d.fdir1 = Eigen::Vector3d(x, y, z).normalized();
  for (const char* attr : {"gz:expressed_in", "ignition:expressed_in", "expressed_in"})
    if (const char* frame = fdir->Attribute(attr)) d.frame = trim(frame);
  if (!d.frame.empty() && !model.link(d.frame))
    problems.push_back(fmt::format("{}:{}: link '{}': <fdir1 expressed_in=\"{}\">: there is no link '{}' to express "
                                   "it in; name a link of the robot (usually the base) or leave the attribute out",
                                   file, fdir->GetLineNum(), l.name, d.frame, d.frame));
  d.mu2 = mu2.value_or(l.friction.value_or(1.0));
  l.friction_direction = d;
}

// A joint's <gazebo reference>: springStiffness, springReference (implicitSpringDamper is how we simulate any spring).
void read_gazebo_joint(Joint& j, const tinyxml2::XMLElement* g, const std::string& file,
                       std::vector<std::string>& problems) {
  const auto k = gazebo_number(g, "springStiffness", file, j.name, true, problems);
  const auto ref = gazebo_number(g, "springReference", file, j.name, false, problems);
  if (k && *k > 0) j.spring = Joint::Spring{*k, ref.value_or(0.0)};
}

// The <gazebo> extensions read here: self_collide (robot); mu1, mu2, fdir1 and turnGravityOff (per link);
// springStiffness, springReference and implicitSpringDamper (per joint); and the gazebo_ros_control plugin (a
// ros2_control plugin is read by ros2_control.cpp). Every other tag is named in one warning: Gazebo would read it, we
// do not.
void parse_gazebo_plugin(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                         std::vector<std::string>& problems) {
  static const std::set<std::string> kLinkTags = {"mu1", "mu2", "fdir1", "turnGravityOff"};
  static const std::set<std::string> kJointTags = {"springStiffness", "springReference", "implicitSpringDamper",
                                                   "provideFeedback"};
  std::map<std::string, int> unread;  // "tag" or "plugin FILENAME" -> count
  for (auto* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    const char* ref = g->Attribute("reference");
    Link* link = nullptr;
    Joint* joint = nullptr;
    if (ref) {
      for (Link& l : model.links)
        if (l.name == ref) link = &l;
      for (Joint& j : model.joints)
        if (j.name == ref) joint = &j;
    }
    for (auto* c = g->FirstChildElement(); c; c = c->NextSiblingElement()) {
      const std::string tag = c->Name();
      const bool read = tag == "plugin" || tag == "sensor" || (!ref && tag == "self_collide") ||
                        (ref && tag == "provideFeedback") || (link && kLinkTags.count(tag)) ||
                        (joint && kJointTags.count(tag));
      if (!read) ++unread[(ref ? "<gazebo reference> " : "<gazebo> ") + tag];
    }
    if (const char* sc = child_text(g, "self_collide"); sc && !ref)
      model.self_collide = trim(sc) == "true" || trim(sc) == "1";
    if (link) read_gazebo_link(model, *link, g, file, problems);
    if (joint) read_gazebo_joint(*joint, g, file, problems);
    for (auto* p = g->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin")) {
      const char* fn = p->Attribute("filename");
      if (fn && std::string(fn).find("gazebo_ros_control") != std::string::npos) {
        model.has_gazebo_ros_control_plugin = true;
        if (const char* ns = child_text(p, "robotNamespace")) model.gazebo_plugin_namespace = trim(ns);
      } else if (!fn || !read_elsewhere(fn)) {
        ++unread[fmt::format("<plugin filename=\"{}\">", fn ? fn : "")];
      }
    }
  }
  if (unread.empty()) return;
  std::vector<std::string> names;
  for (const auto& [tag, n] : unread) names.push_back(n == 1 ? tag : fmt::format("{} (x{})", tag, n));
  model.warnings.push_back(fmt::format("{}: Gazebo tags not simulated here, ignored: {} (read are <self_collide>, "
                                       "per link <mu1>, <mu2>, <fdir1> and <turnGravityOff>, per joint "
                                       "<springStiffness> and <springReference>, the ros_control plugins and the "
                                       "sensors)",
                                       file, fmt::join(names, ", ")));
}

// urdfdom reads a number it cannot parse as 0, or drops the whole element (a mass of "nan" left the link
// massless, silently): every numeric attribute of links and joints must be finite numbers, checked on the XML.
void check_numeric_attributes(const tinyxml2::XMLElement* e, const std::string& file, const std::string& owner,
                              std::vector<std::string>& problems) {
  static const std::map<std::string, std::vector<const char*>> kNumeric = {
      {"mass", {"value"}},
      {"inertia", {"ixx", "ixy", "ixz", "iyy", "iyz", "izz"}},
      {"origin", {"xyz", "rpy"}},
      {"axis", {"xyz"}},
      {"limit", {"lower", "upper", "effort", "velocity"}},
      {"dynamics", {"damping", "friction"}},
      {"safety_controller", {"soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity"}},
      {"mimic", {"multiplier", "offset"}},
      {"box", {"size"}},
      {"cylinder", {"radius", "length"}},
      {"sphere", {"radius"}},
      {"mesh", {"scale"}},
  };
  for (const auto* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    const auto it = kNumeric.find(c->Name());
    if (it != kNumeric.end())
      for (const char* attr : it->second) {
        const char* v = c->Attribute(attr);
        if (!v) continue;
        std::istringstream in(v);
        bool ok = true;
        int count = 0;
        for (std::string tok; in >> tok; ++count) {
          char* end = nullptr;
          const double x = std::strtod(tok.c_str(), &end);
          ok = ok && end && *end == '\0' && std::isfinite(x);
        }
        if (!ok || count == 0)
          problems.push_back(fmt::format("{}:{}: {}: <{} {}=\"{}\"> is not a finite number; write numbers such as 0.5",
                                         file, c->GetLineNum(), owner, c->Name(), attr, v));
      }
    check_numeric_attributes(c, file, owner, problems);
  }
}

}  // namespace

void read_urdf(RobotModel& model, const std::string& urdf_path, const LoadOptions& options,
               std::vector<std::string>& problems) {
  model.urdf_path = urdf_path;
  const std::string text = read_robot_file(urdf_path, options);

  tinyxml2::XMLDocument doc;
  if (doc.Parse(text.c_str(), text.size()) != tinyxml2::XML_SUCCESS) {
    // ErrorStr() is "Error=NAME ErrorID=N (0xN) Line number=N: detail"; keep the name and the detail.
    std::string detail = doc.ErrorStr() ? doc.ErrorStr() : "";
    const auto colon = detail.find(": ");
    detail = colon == std::string::npos ? "" : " at " + trim(detail.substr(colon + 2));
    throw ModelError(fmt::format("{}:{}: malformed XML ({}{})", urdf_path, doc.ErrorLineNum(), doc.ErrorName(), detail));
  }
  const tinyxml2::XMLElement* robot = doc.FirstChildElement("robot");
  if (!robot) throw ModelError(fmt::format("{}: no <robot> element; is this a URDF file?", urdf_path));

  CaptureHandler capture;
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(text);
  console_bridge::restorePreviousOutputHandler();
  for (auto* le = robot->FirstChildElement("link"); le; le = le->NextSiblingElement("link"))
    check_numeric_attributes(le, urdf_path, fmt::format("link '{}'", le->Attribute("name") ? le->Attribute("name") : ""),
                             problems);
  for (auto* je = robot->FirstChildElement("joint"); je; je = je->NextSiblingElement("joint"))
    check_numeric_attributes(je, urdf_path, fmt::format("joint '{}'", je->Attribute("name") ? je->Attribute("name") : ""),
                             problems);
  if (!urdf && !problems.empty()) throw ModelError(problems);  // urdfdom's own words for those are vaguer
  if (!urdf) {
    std::string why = capture.messages.empty() ? "urdfdom could not parse it" : capture.messages.back();
    for (const auto& m : capture.messages)
      if (m.find("rror") != std::string::npos || m.find("ailed") != std::string::npos) {
        why = m;
        break;
      }
    throw ModelError(fmt::format("{}: invalid URDF: {}", urdf_path, why));
  }


  model.name = urdf->getName();
  model.root_link = urdf->getRoot() ? urdf->getRoot()->name : "";
  const std::vector<std::string> package_path = package_path_for(urdf_path, options.package_path);
  const std::string base_dir = fs::absolute(urdf_path).parent_path().string();

  MissingMeshes missing_collision{"collision", urdf_path, base_dir, package_path, {}, {}},
      missing_visual{"visual", urdf_path, base_dir, package_path, {}, {}};
  // URDF document order for links and joints (urdfdom stores them in maps).
  for (auto* le = robot->FirstChildElement("link"); le; le = le->NextSiblingElement("link")) {
    const char* n = le->Attribute("name");
    auto ul = n ? urdf->getLink(n) : nullptr;
    if (!ul) continue;
    Link l;
    l.name = ul->name;
    if (ul->inertial) {
      Inertial in;
      in.mass = ul->inertial->mass;
      in.origin = to_iso(ul->inertial->origin);
      const auto& u = *ul->inertial;
      in.inertia << u.ixx, u.ixy, u.ixz, u.ixy, u.iyy, u.iyz, u.ixz, u.iyz, u.izz;
      l.inertial = in;
    }
    for (const auto& c : ul->collision_array)
      if (c && c->geometry) {
        l.collisions.push_back(to_geometry(c->geometry, c->origin, base_dir, package_path));
        const Geometry& g = l.collisions.back();
        if (g.type == Geometry::Type::Mesh && g.mesh_path.empty()) missing_collision.add(l.name, g.mesh_uri);
      }
    for (const auto& v : ul->visual_array)
      if (v && v->geometry) {
        l.visuals.push_back(to_geometry(v->geometry, v->origin, base_dir, package_path));
        const Geometry& g = l.visuals.back();
        if (g.type == Geometry::Type::Mesh && g.mesh_path.empty()) missing_visual.add(l.name, g.mesh_uri);
      }
    if (ul->parent_joint) l.parent_joint = ul->parent_joint->name;
    model.links.push_back(std::move(l));
  }
  missing_collision.report(problems);
  missing_visual.report(model.warnings);
  for (auto* je = robot->FirstChildElement("joint"); je; je = je->NextSiblingElement("joint")) {
    const char* n = je->Attribute("name");
    auto uj = n ? urdf->getJoint(n) : nullptr;
    if (!uj) continue;
    Joint j;
    j.name = uj->name;
    j.type = to_joint_type(uj->type);
    j.parent_link = uj->parent_link_name;
    j.child_link = uj->child_link_name;
    j.origin = to_iso(uj->parent_to_joint_origin_transform);
    j.axis << uj->axis.x, uj->axis.y, uj->axis.z;
    if (j.type != JointType::Fixed && j.axis.norm() > 0) j.axis.normalize();
    j.effort_limit = j.velocity_limit = INFINITY;
    if (uj->limits) {
      j.effort_limit = uj->limits->effort;
      j.velocity_limit = uj->limits->velocity;
      if (j.type == JointType::Revolute || j.type == JointType::Prismatic) {
        j.has_position_limits = true;
        j.lower = uj->limits->lower;
        j.upper = uj->limits->upper;
      }
    }
    if (uj->dynamics) {
      j.damping = uj->dynamics->damping;
      j.friction = uj->dynamics->friction;
    }
    if (uj->safety)
      j.soft = SoftLimits{uj->safety->soft_lower_limit, uj->safety->soft_upper_limit, uj->safety->k_position,
                          uj->safety->k_velocity};
    if (uj->mimic) j.mimic = Mimic{uj->mimic->joint_name, uj->mimic->multiplier, uj->mimic->offset};
    model.joints.push_back(std::move(j));
  }
  if (has_ros2_control(robot))
    read_ros2_control(model, robot, urdf_path, problems);  // ROS 2: the blocks, not <transmission> tags
  else
    parse_transmissions(model, robot, urdf_path, problems);
  parse_gazebo_plugin(model, robot, urdf_path, problems);
  read_ros2_control_plugin(model, robot, urdf_path, problems);
  read_sensors(model, robot, urdf_path);
}


void load_urdf_into(RobotModel& model, const std::string& urdf_path, const LoadOptions& options) {
  std::vector<std::string> problems;
  read_urdf(model, urdf_path, options, problems);
  if (!problems.empty()) throw ModelError(problems);
}

}  // namespace lcm_control
