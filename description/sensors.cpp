#include "description/sensors.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>

#include "description/robot_model.hpp"
#include "description/text.hpp"

namespace lcm_control {

const char* to_string(SensorKind k) {
  switch (k) {
    case SensorKind::Imu: return "imu";
    case SensorKind::ForceTorque: return "force_torque";
    case SensorKind::Contact: return "contact";
    case SensorKind::Other: return "other";
  }
  return "?";
}

const std::vector<std::string>& sensor_interfaces(SensorKind k) {
  static const std::vector<std::string> imu = {
      "orientation.x",        "orientation.y",        "orientation.z",         "orientation.w",
      "angular_velocity.x",   "angular_velocity.y",   "angular_velocity.z",    "linear_acceleration.x",
      "linear_acceleration.y", "linear_acceleration.z"};
  static const std::vector<std::string> ft = {"force.x", "force.y", "force.z", "torque.x", "torque.y", "torque.z"};
  static const std::vector<std::string> contact = {"contact", "normal_force"};
  static const std::vector<std::string> none;
  switch (k) {
    case SensorKind::Imu: return imu;
    case SensorKind::ForceTorque: return ft;
    case SensorKind::Contact: return contact;
    case SensorKind::Other: return none;
  }
  return none;
}

int sensor_value_count(const std::vector<SensorSpec>& sensors) {
  size_t n = 0;
  for (const SensorSpec& s : sensors)
    if (s.simulated()) n += sensor_interfaces(s.kind).size();
  return int(n);
}

namespace {

const tinyxml2::XMLElement* child(const tinyxml2::XMLElement* e, const char* name) {
  return e ? e->FirstChildElement(name) : nullptr;
}
std::string text(const tinyxml2::XMLElement* e) { return e && e->GetText() ? trim(e->GetText()) : ""; }
std::string attr(const tinyxml2::XMLElement* e, const char* name) {
  const char* v = e ? e->Attribute(name) : nullptr;
  return v ? trim(v) : "";
}

// Reads one sensor's numbers, collecting what cannot be read into `bad` ("<stddev> 'x'") for one warning.
struct Numbers {
  std::vector<std::string>& bad;

  void read(const tinyxml2::XMLElement* e, double& out) {
    if (!e) return;
    double v = 0;
    if (parse_double(text(e), v))
      out = v;
    else
      bad.push_back(fmt::format("<{}> '{}' (line {})", e->Name(), text(e), e->GetLineNum()));
  }
  // Three numbers "x y z" (hector's <accelGaussianNoise>, <xyzOffset>).
  bool read3(const tinyxml2::XMLElement* e, Eigen::Vector3d& out) {
    if (!e) return false;
    const auto w = split_words(text(e));
    Eigen::Vector3d v;
    bool ok = w.size() == 3;
    for (size_t i = 0; ok && i < 3; ++i) ok = parse_double(w[i], v[i]);
    if (!ok) {
      bad.push_back(fmt::format("<{}> '{}' (line {}): three numbers expected", e->Name(), text(e), e->GetLineNum()));
      return false;
    }
    out = v;
    return true;
  }
  // <noise type="gaussian"><mean/><stddev/><bias_mean/><bias_stddev/></noise> (SDF), or the 1.4 form with a
  // <type> child; other noise types are named.
  void noise(const tinyxml2::XMLElement* n, GaussianNoise& out) {
    if (!n) return;
    std::string type = attr(n, "type");
    if (type.empty()) type = text(child(n, "type"));
    if (type == "none") return;
    if (!type.empty() && type != "gaussian" && type != "gaussian_quantized") {
      bad.push_back(fmt::format("<noise type=\"{}\"> (line {}): only gaussian noise is simulated", type,
                                n->GetLineNum()));
      return;
    }
    read(child(n, "mean"), out.mean);
    read(child(n, "stddev"), out.stddev);
    read(child(n, "bias_mean"), out.bias_mean);
    read(child(n, "bias_stddev"), out.bias_stddev);
    if (out.stddev < 0 || out.bias_stddev < 0) {
      bad.push_back(fmt::format("<noise> (line {}): a standard deviation below 0", n->GetLineNum()));
      out = {};
    }
  }
  // <angular_velocity><x><noise>..</x><y>..</y><z>..</z></angular_velocity> (SDF 1.5 on).
  void axis_noise(const tinyxml2::XMLElement* parent, AxisNoise& out) {
    if (!parent) return;
    const char* axes[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) noise(child(child(parent, axes[i]), "noise"), out[i]);
  }
  void same_noise(double stddev, AxisNoise& out) {
    for (auto& n : out) n.stddev = stddev;
  }
};

Eigen::Isometry3d pose_of(const tinyxml2::XMLElement* e, Numbers& num) {
  Eigen::Isometry3d p = Eigen::Isometry3d::Identity();
  if (!e) return p;
  const auto w = split_words(text(e));
  double v[6] = {0, 0, 0, 0, 0, 0};
  bool ok = w.size() == 6;
  for (size_t i = 0; ok && i < 6; ++i) ok = parse_double(w[i], v[i]);
  if (!ok) {
    num.bad.push_back(fmt::format("<pose> '{}' (line {}): six numbers 'x y z roll pitch yaw' expected", text(e),
                                  e->GetLineNum()));
    return p;
  }
  p.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  p.linear() = (Eigen::AngleAxisd(v[5], Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(v[4], Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(v[3], Eigen::Vector3d::UnitX()))
                   .toRotationMatrix();
  return p;
}

bool contains(const std::string& s, const char* part) { return s.find(part) != std::string::npos; }

struct Reader {
  RobotModel& model;
  const std::string& file;

  std::string where(const tinyxml2::XMLElement* e) const { return fmt::format("{}:{}", file, e->GetLineNum()); }

  void finish(SensorSpec s, const std::vector<std::string>& bad) {
    if (!bad.empty())
      model.warnings.push_back(fmt::format("{}: sensor '{}': cannot read {}; it is simulated without them",
                                           s.where, s.name, join(bad, ", ")));
    model.sensors.push_back(std::move(s));
  }

  // Where a <gazebo reference> points: the sensor's link (and, for force-torque, joint); the sensor is marked not
  // simulated when it names neither.
  void place(SensorSpec& s, const std::string& ref) {
    const Joint* j = model.joint(ref);
    const Link* l = model.link(ref);
    if (s.kind == SensorKind::ForceTorque) {
      if (j) {
        s.joint = j->name;
        s.link = j->child_link;
      } else if (l && !l->parent_joint.empty()) {
        s.not_simulated = fmt::format("a force_torque sensor measures a joint, and reference '{}' is a link: "
                                      "write <gazebo reference=\"{}\"> (its parent joint)",
                                      ref, l->parent_joint);
      } else {
        s.not_simulated = fmt::format("reference '{}' is no joint of the URDF", ref);
      }
      return;
    }
    if (l)
      s.link = l->name;
    else if (j)
      s.link = j->child_link;  // Gazebo attaches a sensor named on a joint to its child link
    else
      s.not_simulated = fmt::format("reference '{}' is no link of the URDF", ref);
  }

  // <sensor type=... name=...> inside <gazebo reference="R">.
  void sdf_sensor(const tinyxml2::XMLElement* se, const std::string& ref) {
    SensorSpec s;
    std::vector<std::string> bad;
    Numbers num{bad};
    s.name = attr(se, "name");
    s.type = attr(se, "type");
    s.where = where(se);
    s.topic = text(child(se, "topic"));
    num.read(child(se, "update_rate"), s.update_rate_hz);
    s.pose = pose_of(child(se, "pose"), num);
    if (s.type == "imu") {
      s.kind = SensorKind::Imu;
      const auto* imu = child(se, "imu");
      num.axis_noise(child(imu, "angular_velocity"), s.angular_velocity);
      num.axis_noise(child(imu, "linear_acceleration"), s.linear_acceleration);
      if (const auto* old = child(imu, "noise")) {  // SDF 1.4: <noise><type/><rate/><accel/></noise>
        GaussianNoise rate, accel;
        const std::string type = text(child(old, "type"));
        if (type == "gaussian") {
          num.noise(child(old, "rate"), rate);
          num.noise(child(old, "accel"), accel);
          s.angular_velocity = {rate, rate, rate};
          s.linear_acceleration = {accel, accel, accel};
        }
      }
    } else if (s.type == "force_torque") {
      s.kind = SensorKind::ForceTorque;
      const auto* ft = child(se, "force_torque");
      const std::string frame = text(child(ft, "frame"));
      if (frame == "parent")
        s.frame = WrenchFrame::Parent;
      else if (frame == "sensor")
        s.frame = WrenchFrame::Sensor;
      else if (!frame.empty() && frame != "child")
        bad.push_back(fmt::format("<frame> '{}': child, parent or sensor", frame));
      const std::string dir = text(child(ft, "measure_direction"));
      if (dir == "parent_to_child")
        s.direction = MeasureDirection::ParentToChild;
      else if (!dir.empty() && dir != "child_to_parent")
        bad.push_back(fmt::format("<measure_direction> '{}': child_to_parent or parent_to_child", dir));
      num.axis_noise(child(ft, "force"), s.force);
      num.axis_noise(child(ft, "torque"), s.torque);
    } else if (s.type == "contact") {
      s.kind = SensorKind::Contact;
    } else {
      s.not_simulated = fmt::format("the simulator has no {} sensors (it has imu, force_torque and contact)",
                                    s.type.empty() ? "untyped" : s.type);
    }
    // The ROS plugin inside the sensor: its frame, topic and (classic gazebo_ros_imu_sensor) one noise for all.
    for (auto* p = se->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin")) {
      if (std::string f = text(child(p, "frameName")); !f.empty()) s.frame_id = f;
      if (std::string f = text(child(p, "frame_name")); !f.empty()) s.frame_id = f;
      if (std::string t = text(child(p, "topicName")); !t.empty()) s.topic = t;
      if (s.kind == SensorKind::Imu && child(p, "gaussianNoise")) {
        double sd = 0;
        num.read(child(p, "gaussianNoise"), sd);
        num.same_noise(sd, s.angular_velocity);
        num.same_noise(sd, s.linear_acceleration);
      }
    }
    if (s.simulated()) place(s, ref);
    finish(std::move(s), bad);
  }

  // A model plugin of ROS 1 that is a sensor (gazebo_ros_imu, hector_gazebo_ros_imu, gazebo_ros_ft_sensor); any
  // other plugin is left to the Gazebo-tags warning.
  void plugin_sensor(const tinyxml2::XMLElement* p) {
    const std::string fn = attr(p, "filename");
    const bool hector = contains(fn, "hector_gazebo_ros_imu");
    const bool imu = hector || (contains(fn, "gazebo_ros_imu") && !contains(fn, "gazebo_ros_imu_sensor"));
    const bool ft = contains(fn, "gazebo_ros_ft_sensor");
    if (!imu && !ft) return;
    SensorSpec s;
    std::vector<std::string> bad;
    Numbers num{bad};
    s.name = attr(p, "name");
    s.type = fn;
    s.where = where(p);
    s.kind = imu ? SensorKind::Imu : SensorKind::ForceTorque;
    s.topic = text(child(p, "topicName"));
    s.frame_id = text(child(p, hector ? "frameId" : "frameName"));
    num.read(child(p, "updateRate"), s.update_rate_hz);
    num.read(child(p, "updateRateHZ"), s.update_rate_hz);
    if (ft) {
      // gazebo_ros_ft_sensor: the joint's wrench on its child, in the child frame.
      s.direction = MeasureDirection::ParentToChild;
      double sd = 0;
      num.read(child(p, "gaussianNoise"), sd);
      num.same_noise(sd, s.force);
      num.same_noise(sd, s.torque);
      const std::string joint = text(child(p, "jointName"));
      if (joint.empty())
        s.not_simulated = "it names no <jointName>";
      else
        place(s, joint);
    } else {
      if (hector) {
        Eigen::Vector3d sd = Eigen::Vector3d::Zero(), offset = Eigen::Vector3d::Zero();
        if (num.read3(child(p, "accelGaussianNoise"), sd))
          for (int i = 0; i < 3; ++i) s.linear_acceleration[i].stddev = sd[i];
        if (num.read3(child(p, "rateGaussianNoise"), sd))
          for (int i = 0; i < 3; ++i) s.angular_velocity[i].stddev = sd[i];
        if (num.read3(child(p, "accelOffset"), offset))
          for (int i = 0; i < 3; ++i) s.linear_acceleration[i].mean = offset[i];
        if (num.read3(child(p, "rateOffset"), offset))
          for (int i = 0; i < 3; ++i) s.angular_velocity[i].mean = offset[i];
        for (const char* drift : {"accelDrift", "rateDrift", "yawDrift"})
          if (const auto* d = child(p, drift); d && text(d) != "0" && text(d) != "0 0 0" && text(d) != "0.0 0.0 0.0")
            bad.push_back(fmt::format("<{}> (a random-walk drift, not simulated)", drift));
      } else {
        double sd = 0;
        num.read(child(p, "gaussianNoise"), sd);
        num.same_noise(sd, s.angular_velocity);
        num.same_noise(sd, s.linear_acceleration);
      }
      Eigen::Vector3d xyz = Eigen::Vector3d::Zero(), rpy = Eigen::Vector3d::Zero();
      num.read3(child(p, "xyzOffset"), xyz);
      num.read3(child(p, "rpyOffset"), rpy);
      s.pose.translation() = xyz;
      s.pose.linear() = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                         Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                         Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                            .toRotationMatrix();
      const std::string body = text(child(p, "bodyName"));
      if (body.empty())
        s.not_simulated = "it names no <bodyName>";
      else
        place(s, body);
    }
    finish(std::move(s), bad);
  }

  // A <ros2_control> <sensor>: the Gazebo sensor of that name (gz_ros2_control's rule), or, when none, one placed on
  // its frame_id link with the kind its state interfaces say.
  void ros2_sensor(const HardwareBlock& block, const Ros2Component& c) {
    const std::string frame_id = [&] {
      for (const auto& [k, v] : c.params)
        if (k == "frame_id") return v;
      return std::string();
    }();
    auto named = std::find_if(model.sensors.begin(), model.sensors.end(),
                              [&](const SensorSpec& s) { return s.name == c.name && s.hardware_block.empty(); });
    SensorSpec* s = nullptr;
    if (named != model.sensors.end()) {
      s = &*named;
    } else {
      SensorSpec n;
      n.name = c.name;
      n.type = "ros2_control sensor";
      n.where = fmt::format("{}:{}", file, c.line);
      bool imu = false, ft = false;
      for (const auto& i : c.state_interfaces) {
        imu |= i.name.rfind("orientation.", 0) == 0 || i.name.rfind("angular_velocity.", 0) == 0 ||
               i.name.rfind("linear_acceleration.", 0) == 0;
        ft |= i.name.rfind("force.", 0) == 0 || i.name.rfind("torque.", 0) == 0;
      }
      n.kind = imu && !ft ? SensorKind::Imu : ft && !imu ? SensorKind::ForceTorque : SensorKind::Other;
      if (block.kind == HardwareKind::Mock)
        n.not_simulated = "mock hardware: its state interfaces hold their initial_value";
      else if (n.kind == SensorKind::Other)
        n.not_simulated = "its state interfaces are neither an IMU's nor a force-torque sensor's, and no "
                          "<gazebo reference><sensor name=\"" + c.name + "\"> says what it is";
      else if (frame_id.empty())
        n.not_simulated = "no <gazebo reference=\"LINK\"><sensor name=\"" + c.name +
                          "\"> places it, and it has no frame_id param naming a link";
      else if (const Link* l = model.link(frame_id); !l)
        n.not_simulated = "no <gazebo reference><sensor name=\"" + c.name + "\"> places it, and its frame_id '" +
                          frame_id + "' is no link of the URDF";
      else if (n.kind == SensorKind::ForceTorque && l->parent_joint.empty())
        n.not_simulated = "its frame_id link '" + frame_id + "' is the root: no joint to measure";
      else
        place(n, n.kind == SensorKind::ForceTorque ? l->parent_joint : l->name);
      model.sensors.push_back(std::move(n));
      s = &model.sensors.back();
    }
    s->hardware_block = block.name;
    if (!frame_id.empty()) s->frame_id = frame_id;
    if (!s->simulated()) return;
    const auto& provided = sensor_interfaces(s->kind);
    std::vector<std::string> unknown;
    for (const auto& i : c.state_interfaces)
      if (std::find(provided.begin(), provided.end(), i.name) == provided.end()) unknown.push_back(i.name);
    if (!unknown.empty())
      model.warnings.push_back(fmt::format("{}:{}: ros2_control '{}': sensor '{}' ({}) has state interface{} {} that "
                                           "the simulator does not give (it gives {}); they are not published",
                                           file, c.line, block.name, c.name, to_string(s->kind),
                                           unknown.size() == 1 ? "" : "s", join(unknown), join(provided)));
  }
};

}  // namespace

void read_sensors(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file) {
  Reader r{model, file};
  for (auto* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    const std::string ref = attr(g, "reference");
    for (auto* se = g->FirstChildElement("sensor"); se; se = se->NextSiblingElement("sensor")) {
      if (ref.empty()) {
        SensorSpec s;
        s.name = attr(se, "name");
        s.type = attr(se, "type");
        s.where = r.where(se);
        s.not_simulated = "it is in a <gazebo> without reference=\"LINK\": no link to sit on";
        model.sensors.push_back(std::move(s));
        continue;
      }
      r.sdf_sensor(se, ref);
    }
    for (auto* p = g->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin")) r.plugin_sensor(p);
  }
  for (const HardwareBlock& b : model.ros2_control)
    for (const Ros2Component& c : b.sensors) r.ros2_sensor(b, c);
  for (const SensorSpec& s : model.sensors)
    if (!s.simulated())
      model.warnings.push_back(fmt::format("{}: sensor '{}' ({}) is not simulated: {}", s.where,
                                           s.name.empty() ? "(unnamed)" : s.name, s.type, s.not_simulated));
}

}  // namespace lcm_control
