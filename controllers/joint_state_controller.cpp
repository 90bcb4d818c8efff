// joint_state_controller/JointStateController: publishes `joint_states` at
// publish_rate on the hardware clock, first on its first cycle; `joints` picks
// and orders (default: URDF transmission order, then the mimic joints, whose
// position and velocity follow their joint's by the URDF's <mimic> as ROS's
// joint_state_publisher computes them; effort 0; `publish_mimic_joints: false`
// leaves them out, as ROS's joint_state_controller does); `extra_joints` appends fixed
// values. Unlike ROS it keeps its rate after a forward time jump and resumes
// at once after a backward one (the loop restarts it).
// franka_control/FrankaStateController is the same for what it shares with it:
// joint_states of `joint_names` at publish_rate (franka_states and `arm_id`
// have no equivalent here; a note says so), so franka_gazebo's YAML gives
// joint_states unchanged.
// joint_state_broadcaster/JointStateBroadcaster (ROS 2) publishes every cycle
// (or at its own `update_rate`), every joint unless both `joints` and
// `interfaces` are given (ROS 2's rule); an interface left out is NaN; its
// `extra_joints` are names, published at 0.
#include <fmt/format.h>

#include <array>
#include <limits>

#include "bus/messages.hpp"
#include "controllers/factories.hpp"
#include "controllers/publish_rate.hpp"
#include "lcm_control/joint_state_t.hpp"

namespace lcm_control::cm {

namespace {

enum class Flavour { Ros1, Franka, Ros2 };

class JointStateController : public Controller {
 public:
  explicit JointStateController(Flavour flavour) : flavour_(flavour) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    const bool franka = flavour_ == Flavour::Franka, ros2 = flavour_ == Flavour::Ros2;
    if (!ros2) {  // ROS 2's update_rate is every controller's: the manager updates it that often
      rate_.hz = p.number("publish_rate");
      if (rate_.hz <= 0) throw p.error("publish_rate", fmt::format("{} Hz: must be > 0", rate_.hz));
    }
    const char* joints_key = franka ? "joint_names" : "joints";
    if (franka) {
      if (p.has("arm_id")) p.node("arm_id");
      ctx.notes.push_back(p.where() + ": publishes joint_states only (franka_states has no equivalent here)");
    }
    bool listed = p.has(joints_key);
    if (ros2) read_interfaces(ctx, listed);
    std::vector<std::string> names = listed ? p.strings(joints_key) : ctx.actuated_joints();
    std::vector<std::string> mimic_names;
    for (const auto& n : names) {
      const Joint* j = ctx.model().joint(n);
      if (j && j->mimic)
        mimic_names.push_back(n);
      else
        joints_.push_back(ctx.read(n, joints_key));
    }
    // ROS's joint_state_controller publishes only the joints with a transmission; ours adds their mimic joints unless
    // publish_mimic_joints is false.
    const bool with_mimics = ros2 || p.boolean("publish_mimic_joints", true);
    if (!listed && with_mimics)  // every mimic joint of an actuated joint, after the actuated ones
      for (const Joint& j : ctx.model().joints)
        if (j.mimic && ctx.model().transmission_for_joint(j.mimic->joint)) mimic_names.push_back(j.name);
    names.clear();
    for (const JointData* j : joints_) names.push_back(j->name);
    for (const auto& n : mimic_names) {
      const Mimic& m = *ctx.model().joint(n)->mimic;
      mimics_.push_back(MimicJoint{ctx.read(m.joint, joints_key, n), m.multiplier, m.offset});
      names.push_back(n);
    }
    const YAML::Node extra = p.node("extra_joints");
    if (extra) {
      if (!extra.IsSequence()) throw p.error("extra_joints", "expected a list of {name, position, velocity, effort}");
      for (size_t k = 0; k < extra.size(); ++k) {
        const YAML::Node e = extra[k];
        const std::string where = fmt::format("{}/extra_joints[{}]", p.where(), k);
        const bool bare_name = ros2 && e.IsScalar();  // ROS 2: a name, published at 0
        if (!bare_name && (!e.IsMap() || !e["name"] || !e["name"].IsScalar()))
          throw ControllerError(where + (ros2 ? ": expected a joint name" : ": expected a map with at least `name`"));
        const std::string n = bare_name ? e.Scalar() : e["name"].Scalar();
        bool dup = false;
        for (const auto& x : names) dup = dup || x == n;
        if (dup) {
          ctx.notes.push_back(where + ": joint '" + n + "' is already published; skipped");
          continue;
        }
        Extra x{n, 0, 0, 0};
        for (auto [key, out] : {std::pair{"position", &x.position}, {"velocity", &x.velocity}, {"effort", &x.effort}})
          if (!bare_name && e[key]) {
            try {
              *out = e[key].as<double>();
            } catch (const YAML::Exception&) {
              throw ControllerError(fmt::format("{}/{}: '{}' is not a number", where, key, e[key].Scalar()));
            }
          }
        names.push_back(n);
        extra_.push_back(x);
      }
    }
    resize(msg_, static_cast<int>(names.size()));
    msg_.name = names;
    pub_ = ctx.endpoints().publisher<joint_state_t>(ctx.root_channel(channels::kJointStates));
  }

  void starting(const Time& now) override { rate_.start(now.seconds()); }

  void update(const Time& now, double) override {
    if (!rate_.due(now.seconds())) return;
    msg_.utime = now.utime;
    size_t k = 0;
    for (const JointData* j : joints_) {
      msg_.position[k] = show_[0] ? j->position : kNotPublished;
      msg_.velocity[k] = show_[1] ? j->velocity : kNotPublished;
      msg_.effort[k] = show_[2] ? j->effort : kNotPublished;
      ++k;
    }
    for (const MimicJoint& m : mimics_) {  // as joint_state_publisher does: from the joint it follows
      msg_.position[k] = show_[0] ? m.multiplier * m.leader->position + m.offset : kNotPublished;
      msg_.velocity[k] = show_[1] ? m.multiplier * m.leader->velocity : kNotPublished;
      msg_.effort[k] = show_[2] ? 0 : kNotPublished;  // not measured
      ++k;
    }
    for (const Extra& e : extra_) {
      msg_.position[k] = e.position;
      msg_.velocity[k] = e.velocity;
      msg_.effort[k] = e.effort;
      ++k;
    }
    pub_.publish(msg_);
  }

 private:
  static constexpr double kNotPublished = std::numeric_limits<double>::quiet_NaN();

  // ROS 2's `interfaces` (with `joints`: both given pick, else every joint and interface).
  void read_interfaces(ControllerContext& ctx, bool& joints_listed) {
    Params& p = ctx.params();
    if (!p.has("interfaces")) {
      if (joints_listed) {
        p.node("joints");
        ctx.notes.push_back(p.where() + ": joints without interfaces: every joint is published, as ROS 2's "
                                        "joint_state_broadcaster does (give interfaces too to pick joints)");
        joints_listed = false;
      }
      return;
    }
    const std::vector<std::string> names = p.strings("interfaces");
    if (!joints_listed) {
      ctx.notes.push_back(p.where() + ": interfaces without joints: every interface of every joint is published, as "
                                      "ROS 2's joint_state_broadcaster does");
      return;
    }
    show_ = {false, false, false};
    for (const auto& n : names) {
      const auto i = interface_of_quantity(n);
      if (!i) {
        ctx.notes.push_back(fmt::format("{}/interfaces: '{}' is not in joint_states (position, velocity, effort); "
                                        "not published", p.where(), n));
        continue;
      }
      show_[static_cast<int>(*i)] = true;
    }
  }

  struct Extra {
    std::string name;
    double position, velocity, effort;
  };
  struct MimicJoint {
    const JointData* leader;
    double multiplier, offset;
  };
  Flavour flavour_;
  std::array<bool, 3> show_{true, true, true};  // position, velocity, effort published (else NaN)
  PublishRate rate_;
  std::vector<const JointData*> joints_;
  std::vector<MimicJoint> mimics_;
  std::vector<Extra> extra_;
  joint_state_t msg_;
  Publisher<joint_state_t> pub_;
};

}  // namespace

ControllerType joint_state_controller() {
  ControllerTypeInfo t;
  t.name = "joint_state_controller/JointStateController";
  t.doc = "publishes joint_states of the joints at publish_rate on the hardware clock";
  t.publishes = {channels::kJointStates};
  t.parameters = {
      {"publish_rate", "number", "", "publish_rate", "", "Hz on the hardware clock"},
      {"joints", "strings", "", "", "joints", "which joints and in what order (default: every actuated joint, then the mimic joints)"},
      {"extra_joints", "list", "", "extra_joints", "", "fixed {name, position, velocity, effort} appended"},
      {"publish_mimic_joints", "bool", "true", "", "",
       "false: only the joints with a transmission, as ROS's joint_state_controller (true adds their <mimic> joints)"},
  };
  return {t, [](const std::string&) { return std::make_unique<JointStateController>(Flavour::Ros1); }};
}

ControllerType joint_state_broadcaster() {
  ControllerTypeInfo t;
  t.name = "joint_state_broadcaster/JointStateBroadcaster";
  t.ros = RosVersion::Ros2;
  t.doc = "publishes joint_states of the joints every cycle (or at update_rate) on the hardware clock";
  t.publishes = {channels::kJointStates};
  t.parameters = {
      {"update_rate", "number", "", "", "update_rate", "Hz on the hardware clock (default: every cycle)"},
      {"joints", "strings", "", "", "joints", "with interfaces: which joints and in what order (else every joint)"},
      {"interfaces", "strings", "", "", "interfaces", "with joints: which of position, velocity, effort (others NaN)"},
      {"extra_joints", "strings", "", "", "extra_joints", "names appended, published at 0"},
      {"use_local_topics", "bool", "false", "", "use_local_topics", "joint_states under the controller's name", false},
      {"map_interface_to_joint_state", "map", "", "", "map_interface_to_joint_state",
       "other interfaces published as position, velocity or effort", false},
      {"use_urdf_to_filter", "bool", "true", "", "use_urdf_to_filter", "only joints the URDF has", false},
      {"frame_id", "string", "base_link", "", "frame_id", "header frame of joint_states", false},
  };
  return {t, [](const std::string&) { return std::make_unique<JointStateController>(Flavour::Ros2); }};
}

ControllerType franka_state_controller() {
  ControllerTypeInfo t;
  t.name = "franka_control/FrankaStateController";
  t.doc = "joint_states of joint_names at publish_rate (franka_states has no equivalent here)";
  t.publishes = {channels::kJointStates};
  t.parameters = {
      {"publish_rate", "number", "", "publish_rate", "", "Hz on the hardware clock"},
      {"joint_names", "strings", "", "joint_names", "", "which joints and in what order"},
      {"arm_id", "string", "", "arm_id", "", "read and not used (franka_states is not published)"},
      {"publish_mimic_joints", "bool", "true", "", "",
       "false: only the joints with a transmission, as ROS's joint_state_controller (true adds their <mimic> joints)"},
  };
  return {t, [](const std::string&) { return std::make_unique<JointStateController>(Flavour::Franka); }};
}

}  // namespace lcm_control::cm
