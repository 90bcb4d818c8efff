// The sensors' broadcasters: the hardware's IMU and force-torque readings (hardware_state_t's sensor values) as
// imu_t and wrench_stamped_t.
// imu_sensor_broadcaster/IMUSensorBroadcaster (ROS 2): sensor_name's reading on `<name>/imu` every cycle (or at
// its own update_rate), stamped frame_id.
// force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster (ROS 2): sensor_name's wrench, or the six
// interface_names.force.x..torque.z of one sensor, on `<name>/wrench`.
// imu_sensor_controller/ImuSensorController and force_torque_sensor_controller/ForceTorqueSensorController
// (ROS 1): every IMU (force-torque sensor) of the robot on a channel named after it, at publish_rate, as their
// hardware interfaces' handles are published.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "controllers/factories.hpp"
#include "controllers/publish_rate.hpp"
#include "lcm_control/imu_t.hpp"
#include "lcm_control/wrench_stamped_t.hpp"

namespace lcm_control::cm {

namespace {

void fill(imu_t& m, const SensorData& s) {
  const std::vector<double>& v = s.values;  // sensor_interfaces(Imu) order
  m.orientation = {v[3], v[0], v[1], v[2]};
  m.angular_velocity = {v[4], v[5], v[6]};
  m.linear_acceleration = {v[7], v[8], v[9]};
}

void fill(wrench_stamped_t& m, const SensorData& s) {
  const std::vector<double>& v = s.values;
  m.force = {v[0], v[1], v[2]};
  m.torque = {v[3], v[4], v[5]};
}

template <class Msg>
struct Output {
  const SensorData* sensor;
  Msg msg;
  Publisher<Msg> pub;
};

// One broadcaster of `kind` readings as Msg: ROS 2's (one sensor, on `<name>/<topic>`) or ROS 1's (every sensor of
// the kind, each on its own name, at publish_rate).
template <class Msg>
class SensorBroadcaster : public Controller {
 public:
  SensorBroadcaster(SensorKind kind, bool ros2, const char* topic) : kind_(kind), ros2_(ros2), topic_(topic) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    if (!ros2_) {
      rate_.hz = p.number("publish_rate");
      if (rate_.hz <= 0) throw p.error("publish_rate", fmt::format("{} Hz: must be > 0", rate_.hz));
      for (const SensorSpec& s : ctx.model().sensors)
        if (s.kind == kind_ && s.simulated()) add(ctx, ctx.sensor(s.name, "", kind_), ctx.root_channel(s.name), "");
      if (outputs_.empty())
        ctx.notes.push_back(fmt::format("{}: {} declares no simulated {} sensor; nothing is published", p.where(),
                                        ctx.model().urdf_path, to_string(kind_)));
      return;
    }
    const std::string name = sensor_name(ctx);
    const SensorData* s = ctx.sensor(name, p.has("sensor_name") ? "sensor_name" : "interface_names", kind_);
    std::string frame = p.has("frame_id") ? p.string("frame_id") : "";
    if (frame.empty()) {
      frame = s->frame_id;
      ctx.notes.push_back(fmt::format("{}: no frame_id (ROS 2 requires one); the sensor's frame '{}' is used",
                                      p.where(), frame));
    }
    for (const char* unused : {"static_covariance_orientation", "static_covariance_angular_velocity",
                               "static_covariance_linear_acceleration", "sensor_filter_chain"})
      if (p.has(unused)) p.node(unused);
    add(ctx, s, ctx.channel(topic_), frame);
  }

  void starting(const Time& now) override { rate_.start(now.seconds()); }

  void update(const Time& now, double) override {
    if (!rate_.due(now.seconds())) return;
    for (Output<Msg>& o : outputs_) {
      if (!o.sensor->present) continue;  // the hardware does not send it
      o.msg.utime = now.utime;
      fill(o.msg, *o.sensor);
      o.pub.publish(o.msg);
    }
  }

 private:
  void add(ControllerContext& ctx, const SensorData* s, const std::string& channel, const std::string& frame) {
    Output<Msg> o{s, Msg{}, ctx.endpoints().template publisher<Msg>(channel)};
    o.msg.frame_id = frame.empty() ? s->frame_id : frame;
    outputs_.push_back(std::move(o));
  }

  // ROS 2: sensor_name, or (force-torque) interface_names.force.x ... naming one sensor's interfaces.
  std::string sensor_name(ControllerContext& ctx) {
    Params& p = ctx.params();
    if (p.has("sensor_name") || kind_ != SensorKind::ForceTorque || !p.has("interface_names"))
      return p.string("sensor_name");
    const YAML::Node names = p.node("interface_names");
    std::string sensor;
    for (const std::string& i : sensor_interfaces(kind_)) {
      const auto dot = i.find('.');
      const YAML::Node group = names.IsMap() ? names[i.substr(0, dot)] : YAML::Node();
      const YAML::Node n = group && group.IsMap() ? group[i.substr(dot + 1)] : YAML::Node();
      if (!n || !n.IsScalar()) continue;  // ROS 2 leaves an interface not named out (published as NaN)
      const std::string full = n.Scalar();
      const auto slash = full.rfind('/');
      const std::string owner = slash == std::string::npos ? "" : full.substr(0, slash);
      if (slash == std::string::npos || full.substr(slash + 1) != i)
        throw p.error("interface_names." + i,
                      fmt::format("'{}': this simulator gives a sensor's {} as '<sensor>/{}'", full, i, i));
      if (!sensor.empty() && owner != sensor)
        throw p.error("interface_names." + i, fmt::format("'{}' is of sensor '{}' while the others are of '{}': the "
                                                          "six interfaces must be one sensor's", full, owner, sensor));
      sensor = owner;
    }
    if (sensor.empty()) throw p.error("interface_names", "names none of force.x .. torque.z; give sensor_name instead");
    return sensor;
  }

  SensorKind kind_;
  bool ros2_;
  const char* topic_;
  PublishRate rate_;
  std::vector<Output<Msg>> outputs_;
};

std::vector<ParameterInfo> ros1_parameters(const char* what) {
  return {{"publish_rate", "number", "", "publish_rate", "", fmt::format("Hz on the hardware clock, for every {}", what)}};
}

}  // namespace

ControllerType imu_sensor_broadcaster() {
  ControllerTypeInfo t;
  t.name = "imu_sensor_broadcaster/IMUSensorBroadcaster";
  t.ros = RosVersion::Ros2;
  t.doc = "publishes sensor_name's IMU reading (imu_t) on <name>/imu every cycle";
  t.parameters = {
      ros2_parameter("sensor_name", "string", "", "the IMU: a <sensor> of the URDF"),
      ros2_parameter("frame_id", "string", "", "frame_id of the messages (default: the sensor's frame)"),
      ros2_parameter("update_rate", "number", "", "Hz on the hardware clock (default: every cycle)"),
      ros2_parameter("static_covariance_orientation", "list", "", "covariances (imu_t has none)", false),
      ros2_parameter("static_covariance_angular_velocity", "list", "", "covariances (imu_t has none)", false),
      ros2_parameter("static_covariance_linear_acceleration", "list", "", "covariances (imu_t has none)", false),
  };
  return {t, [](const std::string&) {
            return std::make_unique<SensorBroadcaster<imu_t>>(SensorKind::Imu, true, "imu");
          }};
}

ControllerType force_torque_sensor_broadcaster() {
  ControllerTypeInfo t;
  t.name = "force_torque_sensor_broadcaster/ForceTorqueSensorBroadcaster";
  t.ros = RosVersion::Ros2;
  t.doc = "publishes sensor_name's wrench (wrench_stamped_t) on <name>/wrench every cycle";
  t.parameters = {
      ros2_parameter("sensor_name", "string", "", "the force-torque sensor: a <sensor> of the URDF"),
      ros2_parameter("interface_names", "map", "", "force.x .. torque.z as '<sensor>/force.x' (instead of sensor_name)"),
      ros2_parameter("frame_id", "string", "", "frame_id of the messages (default: the sensor's frame)"),
      ros2_parameter("update_rate", "number", "", "Hz on the hardware clock (default: every cycle)"),
      ros2_parameter("sensor_filter_chain", "map", "", "filters for wrench_filtered", false),
  };
  return {t, [](const std::string&) {
            return std::make_unique<SensorBroadcaster<wrench_stamped_t>>(SensorKind::ForceTorque, true, "wrench");
          }};
}

ControllerType imu_sensor_controller() {
  ControllerTypeInfo t;
  t.name = "imu_sensor_controller/ImuSensorController";
  t.doc = "publishes every IMU of the robot (imu_t) on a channel named after it, at publish_rate";
  t.parameters = ros1_parameters("IMU");
  return {t, [](const std::string&) {
            return std::make_unique<SensorBroadcaster<imu_t>>(SensorKind::Imu, false, "");
          }};
}

ControllerType force_torque_sensor_controller() {
  ControllerTypeInfo t;
  t.name = "force_torque_sensor_controller/ForceTorqueSensorController";
  t.doc = "publishes every force-torque sensor of the robot (wrench_stamped_t) on a channel named after it, at "
          "publish_rate";
  t.parameters = ros1_parameters("force-torque sensor");
  return {t, [](const std::string&) {
            return std::make_unique<SensorBroadcaster<wrench_stamped_t>>(SensorKind::ForceTorque, false, "");
          }};
}

}  // namespace lcm_control::cm
