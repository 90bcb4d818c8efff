#include "common/robot_model.hpp"

#include <console_bridge/console.h>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tinyxml2.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

namespace fs = std::filesystem;

namespace lcm_control {

namespace {

std::string join_lines(const std::vector<std::string>& v) {
  std::string s;
  for (size_t k = 0; k < v.size(); ++k) s += (k ? "\n" : "") + v[k];
  return s;
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

std::string read_file(const std::string& path, const char* what) {
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw ModelError(fmt::format("{}: {} file not found (check the path passed with --{})", path, what,
                                 std::string(what) == "URDF" ? "urdf" : "config"));
  if (fs::is_directory(path, ec)) throw ModelError(fmt::format("{}: is a folder, expected a {} file", path, what));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ModelError(fmt::format("{}: cannot read the {} file (permissions?)", path, what));
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

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

bool parse_double(const std::string& text, double& out) {
  const std::string t = trim(text);
  if (t.empty()) return false;
  char* end = nullptr;
  out = std::strtod(t.c_str(), &end);
  return end && *end == '\0' && std::isfinite(out);
}

std::string names_of(const std::vector<Joint>& joints, bool moving_only) {
  std::vector<std::string> n;
  for (const auto& j : joints)
    if (!moving_only || j.type != JointType::Fixed) n.push_back(j.name);
  return n.empty() ? "none" : fmt::format("{}", fmt::join(n, ", "));
}

void parse_transmissions(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                         std::vector<std::string>& problems) {
  for (auto* t = robot->FirstChildElement("transmission"); t; t = t->NextSiblingElement("transmission")) {
    TransmissionSpec spec;
    const char* tname = t->Attribute("name");
    spec.name = tname ? tname : "";
    const std::string where = fmt::format("{}:{}: transmission '{}'", file, t->GetLineNum(), spec.name);
    if (spec.name.empty()) problems.push_back(fmt::format("{}: has no name attribute; add name=\"...\"", where));

    if (const char* type = child_text(t, "type")) spec.type = trim(type);
    if (spec.type.empty()) {
      // ROS's old-style <transmission type="..."> attribute.
      if (const char* a = t->Attribute("type")) spec.type = trim(a);
    }
    if (spec.type.empty()) {
      problems.push_back(fmt::format("{}: no <type>; add <type>transmission_interface/SimpleTransmission</type>", where));
      continue;
    }
    if (spec.type != "transmission_interface/SimpleTransmission" && spec.type != "SimpleTransmission") {
      problems.push_back(fmt::format("{}: type '{}' is not supported; only transmission_interface/SimpleTransmission is",
                                     where, spec.type));
      continue;
    }

    int n_joints = 0, n_actuators = 0;
    for (auto* j = t->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) ++n_joints;
    for (auto* a = t->FirstChildElement("actuator"); a; a = a->NextSiblingElement("actuator")) ++n_actuators;
    if (n_joints != 1 || n_actuators != 1) {
      problems.push_back(fmt::format("{}: SimpleTransmission needs exactly one <joint> and one <actuator> (found {} and {})",
                                     where, n_joints, n_actuators));
      continue;
    }
    auto* je = t->FirstChildElement("joint");
    const char* jn = je->Attribute("name");
    spec.joint = jn ? jn : "";
    if (spec.joint.empty()) {
      problems.push_back(fmt::format("{}: <joint> has no name attribute", where));
      continue;
    }
    for (auto* hi = je->FirstChildElement("hardwareInterface"); hi; hi = hi->NextSiblingElement("hardwareInterface")) {
      const std::string text = trim(hi->GetText() ? hi->GetText() : "");
      auto iface = parse_interface(text);
      if (!iface) {
        problems.push_back(fmt::format(
            "{}: joint '{}': unknown hardwareInterface '{}'; use hardware_interface/PositionJointInterface, "
            "VelocityJointInterface or EffortJointInterface",
            where, spec.joint, text));
        continue;
      }
      if (std::find(spec.interfaces.begin(), spec.interfaces.end(), *iface) == spec.interfaces.end())
        spec.interfaces.push_back(*iface);
    }
    auto* ae = t->FirstChildElement("actuator");
    if (spec.interfaces.empty()) {
      // Deprecated in ROS, still accepted: the interface on the actuator.
      for (auto* hi = ae->FirstChildElement("hardwareInterface"); hi; hi = hi->NextSiblingElement("hardwareInterface")) {
        auto iface = parse_interface(trim(hi->GetText() ? hi->GetText() : ""));
        if (iface) spec.interfaces.push_back(*iface);
      }
      if (!spec.interfaces.empty())
        model.warnings.push_back(fmt::format("{}: hardwareInterface given on the actuator; move it into <joint name=\"{}\">",
                                             where, spec.joint));
    }
    if (spec.interfaces.empty()) {
      bool reported = false;
      for (const auto& p : problems) reported = reported || p.rfind(where, 0) == 0;
      if (!reported)
        problems.push_back(fmt::format(
            "{}: joint '{}' has no <hardwareInterface>; add hardware_interface/PositionJointInterface, "
            "VelocityJointInterface or EffortJointInterface",
            where, spec.joint));
      continue;
    }
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
      model.warnings.push_back(
          fmt::format("{}: actuator '{}' has no <mechanicalReduction>; using 1", where, spec.actuator));
    }
    model.transmissions.push_back(std::move(spec));
  }

  for (auto* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    for (auto* p = g->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin")) {
      const char* fn = p->Attribute("filename");
      if (fn && std::string(fn).find("gazebo_ros_control") != std::string::npos) {
        model.has_gazebo_ros_control_plugin = true;
        if (const char* ns = child_text(p, "robotNamespace")) model.gazebo_plugin_namespace = trim(ns);
      }
    }
  }
}

}  // namespace

PidGains parse_pid_gains(const YAML::Node& n, const std::string& where, std::vector<std::string>& problems,
                         std::vector<std::string>& warnings) {
  PidGains g;
  static const std::set<std::string> known = {"p", "i", "d", "i_clamp", "i_clamp_min", "i_clamp_max", "antiwindup",
                                              "publish_state"};
  if (!n.IsMap()) {
    problems.push_back(fmt::format("{}: expected a map with p, i, d (got a {})", where, n.IsSequence() ? "list" : "scalar"));
    return g;
  }
  for (const auto& kv : n) {
    const std::string key = kv.first.as<std::string>();
    if (!known.count(key))
      problems.push_back(fmt::format("{}/{}: unknown key; valid keys are p, i, d, i_clamp, i_clamp_min, i_clamp_max, "
                                     "antiwindup",
                                     where, key));
  }
  auto num = [&](const char* key, double& out) {
    if (!n[key]) return false;
    try {
      out = n[key].as<double>();
      if (!std::isfinite(out)) throw YAML::Exception(YAML::Mark::null_mark(), "not finite");
      return true;
    } catch (const YAML::Exception&) {
      problems.push_back(fmt::format("{}/{}: '{}' is not a number", where, key, n[key].Scalar()));
      return false;
    }
  };
  if (!num("p", g.p))
    if (!n["p"]) problems.push_back(fmt::format("{}: no 'p' gain (required); add p: <value>", where));
  num("i", g.i);
  num("d", g.d);
  double c = 0;
  if (num("i_clamp", c)) {
    g.i_clamp_max = std::abs(c);
    g.i_clamp_min = -std::abs(c);
  }
  if (num("i_clamp_min", c)) g.i_clamp_min = -std::abs(c);
  if (num("i_clamp_max", c)) g.i_clamp_max = std::abs(c);
  if (n["antiwindup"]) {
    try {
      g.antiwindup = n["antiwindup"].as<bool>();
    } catch (const YAML::Exception&) {
      problems.push_back(fmt::format("{}/antiwindup: '{}' is not true or false", where, n["antiwindup"].Scalar()));
    }
  }
  if (g.i != 0 && g.i_clamp_min == 0 && g.i_clamp_max == 0)
    warnings.push_back(fmt::format("{}: i is {} but i_clamp is 0, so the integral term stays 0 (ros_control semantics); "
                                   "set i_clamp to use it",
                                   where, g.i));
  return g;
}

ModelError::ModelError(const std::vector<std::string>& problems)
    : std::runtime_error(join_lines(problems)), problems_(problems) {}

const char* to_string(JointType t) {
  switch (t) {
    case JointType::Revolute: return "revolute";
    case JointType::Continuous: return "continuous";
    case JointType::Prismatic: return "prismatic";
    case JointType::Fixed: return "fixed";
    case JointType::Floating: return "floating";
    case JointType::Planar: return "planar";
  }
  return "?";
}

const char* to_string(Interface i) {
  switch (i) {
    case Interface::Position: return "PositionJointInterface";
    case Interface::Velocity: return "VelocityJointInterface";
    case Interface::Effort: return "EffortJointInterface";
  }
  return "?";
}

std::optional<Interface> parse_interface(const std::string& raw) {
  std::string n = trim(raw);
  const std::string prefix = "hardware_interface/";
  if (n.rfind(prefix, 0) == 0) n = n.substr(prefix.size());
  if (n == "PositionJointInterface") return Interface::Position;
  if (n == "VelocityJointInterface") return Interface::Velocity;
  if (n == "EffortJointInterface") return Interface::Effort;
  return std::nullopt;
}

const Joint* RobotModel::joint(const std::string& n) const {
  for (const auto& j : joints)
    if (j.name == n) return &j;
  return nullptr;
}
const Link* RobotModel::link(const std::string& n) const {
  for (const auto& l : links)
    if (l.name == n) return &l;
  return nullptr;
}
const TransmissionSpec* RobotModel::transmission_for_joint(const std::string& j) const {
  for (const auto& t : transmissions)
    if (t.joint == j) return &t;
  return nullptr;
}
const ControllerSpec* RobotModel::controller(const std::string& n) const {
  for (const auto& c : controllers)
    if (c.name == n) return &c;
  return nullptr;
}
std::vector<std::string> RobotModel::actuated_joints() const {
  std::vector<std::string> v;
  for (const auto& t : transmissions) v.push_back(t.joint);
  return v;
}

std::vector<std::string> default_package_path() {
  std::vector<std::string> out;
  for (const char* var : {"LCM_CONTROL_PACKAGE_PATH", "ROS_PACKAGE_PATH"}) {
    const char* v = std::getenv(var);
    if (!v) continue;
    std::stringstream ss(v);
    std::string item;
    while (std::getline(ss, item, ':'))
      if (!item.empty()) out.push_back(item);
  }
  return out;
}

std::string find_package_dir(const std::string& name, const std::vector<std::string>& package_path) {
  std::error_code ec;
  for (const auto& dir : package_path) {
    const fs::path d(dir);
    if (d.filename() == name && fs::is_directory(d, ec)) return d.string();
    if (fs::is_directory(d / name, ec)) return (d / name).string();
    // One level deeper, as a catkin workspace's src/ holds packages in sub-folders.
    for (fs::directory_iterator it(d, ec), end; !ec && it != end; it.increment(ec))
      if (it->is_directory(ec) && fs::is_directory(it->path() / name, ec)) return (it->path() / name).string();
  }
  return "";
}

std::string resolve_resource(const std::string& uri, const std::string& base_dir,
                             const std::vector<std::string>& package_path) {
  std::error_code ec;
  const std::string pkg = "package://", file = "file://";
  if (uri.rfind(pkg, 0) == 0) {
    const std::string rest = uri.substr(pkg.size());
    const auto slash = rest.find('/');
    if (slash == std::string::npos) return "";
    const std::string dir = find_package_dir(rest.substr(0, slash), package_path);
    if (dir.empty()) return "";
    const fs::path p = fs::path(dir) / rest.substr(slash + 1);
    return fs::exists(p, ec) ? fs::weakly_canonical(p, ec).string() : "";
  }
  fs::path p = uri.rfind(file, 0) == 0 ? fs::path(uri.substr(file.size())) : fs::path(uri);
  if (p.is_relative()) p = fs::path(base_dir) / p;
  return fs::exists(p, ec) ? fs::weakly_canonical(p, ec).string() : "";
}

namespace {

// Fills `model`; throws at once only when the file cannot be parsed at all,
// otherwise adds every problem to `problems` so that all are reported together.
void load_urdf_collect(RobotModel& model, const std::string& urdf_path, const LoadOptions& options,
                       std::vector<std::string>& problems) {
  model.urdf_path = urdf_path;
  const std::string text = read_file(urdf_path, "URDF");

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
  const LoadOptions resolved{options.package_path.empty() ? default_package_path() : options.package_path};
  const std::string base_dir = fs::absolute(urdf_path).parent_path().string();

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
        l.collisions.push_back(to_geometry(c->geometry, c->origin, base_dir, resolved.package_path));
        const Geometry& g = l.collisions.back();
        if (g.type == Geometry::Type::Mesh && g.mesh_path.empty())
          problems.push_back(fmt::format(
              "{}: link '{}': collision mesh '{}' not found (relative paths are read from {}; package:// is searched "
              "in --package-path / LCM_CONTROL_PACKAGE_PATH / ROS_PACKAGE_PATH: {})",
              urdf_path, l.name, g.mesh_uri, base_dir,
              resolved.package_path.empty() ? "empty" : fmt::format("{}", fmt::join(resolved.package_path, ":"))));
      }
    for (const auto& v : ul->visual_array)
      if (v && v->geometry) {
        l.visuals.push_back(to_geometry(v->geometry, v->origin, base_dir, resolved.package_path));
        const Geometry& g = l.visuals.back();
        if (g.type == Geometry::Type::Mesh && g.mesh_path.empty())
          model.warnings.push_back(
              fmt::format("{}: link '{}': visual mesh '{}' not found", urdf_path, l.name, g.mesh_uri));
      }
    if (ul->parent_joint) l.parent_joint = ul->parent_joint->name;
    model.links.push_back(std::move(l));
  }
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
    model.joints.push_back(std::move(j));
  }
  parse_transmissions(model, robot, urdf_path, problems);
}

void validate_collect(RobotModel& model, std::vector<std::string>& problems);

}  // namespace

void load_urdf_into(RobotModel& model, const std::string& urdf_path, const LoadOptions& options) {
  std::vector<std::string> problems;
  load_urdf_collect(model, urdf_path, options, problems);
  if (!problems.empty()) throw ModelError(problems);
}

void parse_control_config(RobotModel& model, const YAML::Node& root, const std::string& file) {
  std::vector<std::string> problems;
  if (!root || root.IsNull()) throw ModelError(fmt::format("{}: the file is empty; expected controllers as top-level keys", file));
  if (!root.IsMap())
    throw ModelError(fmt::format("{}: expected a map of controllers at the top level (like `j1_controller: {{type: ...}}`)",
                                 file));
  for (const auto& kv : root) {
    const std::string key = kv.first.as<std::string>();
    const YAML::Node& v = kv.second;
    if (key == "gazebo_ros_control") {
      if (!v.IsMap()) {
        problems.push_back(fmt::format("{}: gazebo_ros_control: expected a map with pid_gains", file));
        continue;
      }
      for (const auto& g : v) {
        const std::string gk = g.first.as<std::string>();
        if (gk != "pid_gains") {
          model.warnings.push_back(fmt::format("{}: gazebo_ros_control/{}: not used (only pid_gains is read)", file, gk));
          continue;
        }
        if (!g.second.IsMap()) {
          problems.push_back(fmt::format("{}: gazebo_ros_control/pid_gains: expected a map of joint names", file));
          continue;
        }
        for (const auto& jg : g.second) {
          const std::string joint = jg.first.as<std::string>();
          model.pid_gains[joint] = parse_pid_gains(
              jg.second, fmt::format("{}: gazebo_ros_control/pid_gains/{}", file, joint), problems, model.warnings);
        }
      }
      continue;
    }
    if (!v.IsMap() || !v["type"]) {
      model.warnings.push_back(fmt::format(
          "{}: top-level entry '{}' is neither a controller (no 'type' key) nor gazebo_ros_control; it is ignored", file,
          key));
      continue;
    }
    if (!v["type"].IsScalar() || trim(v["type"].Scalar()).empty()) {
      problems.push_back(fmt::format("{}: {}/type: expected a controller type name such as "
                                     "position_controllers/JointPositionController",
                                     file, key));
      continue;
    }
    model.controllers.push_back(ControllerSpec{key, trim(v["type"].Scalar()), YAML::Clone(v)});
  }
  if (!problems.empty()) throw ModelError(problems);
}

void load_control_config_into(RobotModel& model, const std::string& config_path) {
  model.config_path = config_path;
  const std::string text = read_file(config_path, "config");
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw ModelError(fmt::format("{}:{}:{}: malformed YAML: {}", config_path, e.mark.line + 1, e.mark.column + 1, e.msg));
  }
  parse_control_config(model, root, config_path);
}

void validate(RobotModel& model) {
  std::vector<std::string> problems;
  validate_collect(model, problems);
  if (!problems.empty()) throw ModelError(problems);
}

namespace {
void validate_collect(RobotModel& model, std::vector<std::string>& problems) {
  const std::string& u = model.urdf_path;
  const std::string& c = model.config_path;

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
      else if (j.type == JointType::Revolute && j.upper - j.lower > 2 * M_PI)
        problems.push_back(fmt::format("{}: joint '{}': limits [{}, {}] span {:.4f} rad, more than 2*pi, so they overlap; "
                                       "narrow them or make the joint continuous",
                                       u, j.name, j.lower, j.upper, j.upper - j.lower));
    }
    if (j.effort_limit == 0)
      problems.push_back(fmt::format("{}: joint '{}': <limit effort=\"0\"> would freeze the joint (no force allowed); set "
                                     "the actuator's real effort limit",
                                     u, j.name));
    if (j.velocity_limit == 0)
      problems.push_back(fmt::format("{}: joint '{}': <limit velocity=\"0\"> would freeze the joint; set the real "
                                     "velocity limit",
                                     u, j.name));
    if (j.effort_limit < 0 || j.velocity_limit < 0)
      problems.push_back(fmt::format("{}: joint '{}': effort and velocity limits must be positive", u, j.name));
    if (j.damping < 0 || j.friction < 0)
      problems.push_back(fmt::format("{}: joint '{}': damping and friction must be >= 0", u, j.name));
  }
  for (const auto& l : model.links)
    if (l.inertial && l.inertial->mass < 0)
      problems.push_back(fmt::format("{}: link '{}': negative mass {}", u, l.name, l.inertial->mass));

  std::set<std::string> seen_joints, seen_actuators;
  for (const auto& t : model.transmissions) {
    const Joint* j = model.joint(t.joint);
    if (!j) {
      problems.push_back(fmt::format("{}: transmission '{}' names joint '{}', which is not in the URDF (moving joints: {})",
                                     u, t.name, t.joint, names_of(model.joints, true)));
      continue;
    }
    if (j->type == JointType::Fixed)
      problems.push_back(fmt::format("{}: transmission '{}': joint '{}' is fixed and cannot be actuated", u, t.name, t.joint));
    if (!seen_joints.insert(t.joint).second)
      problems.push_back(fmt::format("{}: joint '{}' has more than one transmission ('{}' is the second)", u, t.joint, t.name));
    if (!seen_actuators.insert(t.actuator).second)
      problems.push_back(fmt::format("{}: actuator name '{}' is used by more than one transmission", u, t.actuator));
  }

  for (const auto& [joint, gains] : model.pid_gains) {
    const Joint* j = model.joint(joint);
    const TransmissionSpec* t = model.transmission_for_joint(joint);
    if (!j) {
      problems.push_back(fmt::format("{}: gazebo_ros_control/pid_gains/{}: joint '{}' is not in the URDF {} (moving "
                                     "joints: {})",
                                     c, joint, joint, u, names_of(model.joints, true)));
    } else if (!t) {
      model.warnings.push_back(fmt::format("{}: gazebo_ros_control/pid_gains/{}: joint has no transmission in {}, so the "
                                           "gains are not used",
                                           c, joint, u));
    } else if (t->interfaces.front() == Interface::Effort) {
      model.warnings.push_back(fmt::format("{}: gazebo_ros_control/pid_gains/{}: the joint takes effort commands, so "
                                           "the gains are not used",
                                           c, joint));
    }
    (void)gains;
  }
  std::set<std::string> names;
  for (const auto& ctl : model.controllers)
    if (!names.insert(ctl.name).second)
      problems.push_back(fmt::format("{}: controller '{}' is defined twice", c, ctl.name));
  if (!model.transmissions.empty() && !model.has_gazebo_ros_control_plugin)
    model.warnings.push_back(fmt::format("{}: no <gazebo><plugin filename=\"libgazebo_ros_control.so\"/>; not needed "
                                         "here, but ROS would not start ros_control without it",
                                         u));
}
}  // namespace

RobotModel load_robot_model(const std::string& urdf_path, const std::string& config_path, const LoadOptions& options) {
  RobotModel model;
  std::vector<std::string> problems;
  bool parsed = true;
  try {
    load_urdf_collect(model, urdf_path, options, problems);
  } catch (const ModelError& e) {
    parsed = false;
    problems.insert(problems.end(), e.problems().begin(), e.problems().end());
  }
  if (!config_path.empty()) {
    try {
      load_control_config_into(model, config_path);
    } catch (const ModelError& e) {
      parsed = false;
      problems.insert(problems.end(), e.problems().begin(), e.problems().end());
    }
  }
  if (parsed) validate_collect(model, problems);
  if (!problems.empty()) throw ModelError(problems);
  return model;
}

std::string describe(const RobotModel& m) {
  std::string s;
  auto out = std::back_inserter(s);
  fmt::format_to(out, "robot '{}' from {}\n", m.name, m.urdf_path);
  if (!m.config_path.empty()) fmt::format_to(out, "config from {}\n", m.config_path);
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
  fmt::format_to(out, "\njoints ({}):\n", m.joints.size());
  for (const auto& j : m.joints) {
    const auto& o = j.origin.translation();
    fmt::format_to(out, "  {:<16} {:<10} {} -> {}, origin ({:g}, {:g}, {:g})", j.name, to_string(j.type), j.parent_link,
                   j.child_link, o.x(), o.y(), o.z());
    if (j.type != JointType::Fixed) {
      fmt::format_to(out, ", axis ({:g}, {:g}, {:g})", j.axis.x(), j.axis.y(), j.axis.z());
      if (j.has_position_limits) fmt::format_to(out, ", limits [{:g}, {:g}]", j.lower, j.upper);
      fmt::format_to(out, ", effort {:g}, velocity {:g}, damping {:g}, friction {:g}", j.effort_limit, j.velocity_limit,
                     j.damping, j.friction);
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
  fmt::format_to(out, "gazebo_ros_control plugin tag: {}\n", m.has_gazebo_ros_control_plugin ? "yes" : "no");
  fmt::format_to(out, "\ncontrollers ({}):\n", m.controllers.size());
  for (const auto& c : m.controllers) fmt::format_to(out, "  {:<24} {}\n", c.name, c.type);
  if (!m.warnings.empty()) {
    fmt::format_to(out, "\nwarnings ({}):\n", m.warnings.size());
    for (const auto& w : m.warnings) fmt::format_to(out, "  {}\n", w);
  }
  return s;
}

}  // namespace lcm_control
