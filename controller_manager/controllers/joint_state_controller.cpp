// joint_state_controller/JointStateController: publishes `joint_states` at
// publish_rate on the hardware clock, first on its first cycle; `joints` picks
// and orders (default: URDF transmission order, then the mimic joints, whose
// position and velocity follow their joint's by the URDF's <mimic> as ROS's
// joint_state_publisher computes them; effort 0); `extra_joints` appends fixed
// values. Unlike ROS it keeps its rate after a forward time jump and resumes
// at once after a backward one (the loop restarts it).
// franka_control/FrankaStateController is the same for what it shares with it:
// joint_states of `joint_names` at publish_rate (franka_states and `arm_id`
// have no equivalent here; a note says so), so franka_gazebo's YAML gives
// joint_states unchanged.
#include <fmt/format.h>

#include "bus/messages.hpp"
#include "controller_manager/controllers/factories.hpp"
#include "lcm_control/joint_state_t.hpp"

namespace lcm_control::cm {

namespace {

class JointStateController : public Controller {
 public:
  explicit JointStateController(bool franka) : franka_(franka) {}

  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    rate_ = p.number("publish_rate");
    if (rate_ <= 0) throw p.error("publish_rate", fmt::format("{} Hz: must be > 0", rate_));
    const char* joints_key = franka_ ? "joint_names" : "joints";
    if (franka_) {
      if (p.has("arm_id")) p.node("arm_id");
      ctx.notes.push_back(p.where() + ": publishes joint_states only (franka_states has no equivalent here)");
    }
    const bool listed = p.has(joints_key);
    std::vector<std::string> names = listed ? p.strings(joints_key) : ctx.actuated_joints();
    std::vector<std::string> mimic_names;
    for (const auto& n : names) {
      const Joint* j = ctx.model().joint(n);
      if (j && j->mimic)
        mimic_names.push_back(n);
      else
        joints_.push_back(ctx.read(n, joints_key));
    }
    if (!listed)  // every mimic joint of an actuated joint, after the actuated ones
      for (const Joint& j : ctx.model().joints)
        if (j.mimic && ctx.model().transmission_for_joint(j.mimic->joint)) mimic_names.push_back(j.name);
    names.clear();
    for (const JointData* j : joints_) names.push_back(j->name);
    for (const auto& n : mimic_names) {
      const Mimic& m = *ctx.model().joint(n)->mimic;
      mimics_.push_back(MimicJoint{ctx.read(m.joint, joints_key), m.multiplier, m.offset});
      names.push_back(n);
    }
    const YAML::Node extra = p.node("extra_joints");
    if (extra) {
      if (!extra.IsSequence()) throw p.error("extra_joints", "expected a list of {name, position, velocity, effort}");
      for (size_t k = 0; k < extra.size(); ++k) {
        const YAML::Node e = extra[k];
        const std::string where = fmt::format("{}/extra_joints[{}]", p.where(), k);
        if (!e.IsMap() || !e["name"] || !e["name"].IsScalar())
          throw ControllerError(where + ": expected a map with at least `name`");
        const std::string n = e["name"].Scalar();
        bool dup = false;
        for (const auto& x : names) dup = dup || x == n;
        if (dup) {
          ctx.notes.push_back(where + ": joint '" + n + "' is already published; skipped");
          continue;
        }
        Extra x{n, 0, 0, 0};
        for (auto [key, out] : {std::pair{"position", &x.position}, {"velocity", &x.velocity}, {"effort", &x.effort}})
          if (e[key]) {
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

  void starting(const Time& now) override { last_ = now.seconds() - 1.001 / rate_; }

  void update(const Time& now, double) override {
    const double t = now.seconds(), dt = 1.0 / rate_;
    if (t < last_) last_ = t - 1.001 * dt;
    if (!(last_ + dt < t)) return;
    last_ += dt;
    if (t - last_ > dt) last_ = t;  // fell behind (time jump, slow loop): no burst to catch up
    msg_.utime = now.utime;
    size_t k = 0;
    for (const JointData* j : joints_) {
      msg_.position[k] = j->position;
      msg_.velocity[k] = j->velocity;
      msg_.effort[k] = j->effort;
      ++k;
    }
    for (const MimicJoint& m : mimics_) {  // as joint_state_publisher does: from the joint it follows
      msg_.position[k] = m.multiplier * m.leader->position + m.offset;
      msg_.velocity[k] = m.multiplier * m.leader->velocity;
      msg_.effort[k] = 0;  // not measured
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
  struct Extra {
    std::string name;
    double position, velocity, effort;
  };
  struct MimicJoint {
    const JointData* leader;
    double multiplier, offset;
  };
  bool franka_;
  double rate_ = 0, last_ = 0;
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
  t.ros2_names = {"joint_state_broadcaster/JointStateBroadcaster"};
  t.doc = "publishes joint_states of the joints at publish_rate on the hardware clock";
  t.publishes = {channels::kJointStates};
  t.parameters = {
      {"publish_rate", "number", "", "publish_rate", "", "Hz on the hardware clock"},
      {"joints", "strings", "", "", "joints", "which joints and in what order (default: every actuated joint, then the mimic joints)"},
      {"extra_joints", "list", "", "extra_joints", "", "fixed {name, position, velocity, effort} appended"},
  };
  return {t, [](const std::string&) { return std::make_unique<JointStateController>(false); }};
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
  };
  return {t, [](const std::string&) { return std::make_unique<JointStateController>(true); }};
}

}  // namespace lcm_control::cm
