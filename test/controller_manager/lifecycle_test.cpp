// Hardware components' lifecycle in the loop (test/robots/two_component_arm: an arm, a gripper and a wrist IMU, each
// its own <ros2_control> block): a component leaving active stops exactly the controllers that command it (those
// that read it too when it becomes unconfigured), in the cycle it changes; its actuators are no longer commanded;
// a controller cannot start on a component that does not allow it; a component the hardware reports in error is
// set unconfigured and its controllers stopped in the cycle the error arrives; states from the parameter file.
#include <gtest/gtest.h>

#include <fstream>
#include <optional>

#include "test/controller_manager/rig.hpp"
#include "controllers/builtin.hpp"

using namespace lcm_control;
using namespace lcm_control::cm;
using lcm_control::testing::Rig;
namespace lt = lcm_control::testing;

namespace {
bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

const std::string kUrdf = lt::source("test/robots/two_component_arm.urdf");
const std::string kYaml = lt::source("test/robots/two_component_arm.yaml");

struct ArmRig : Rig {
  explicit ArmRig(const std::string& yaml = kYaml) : Rig(builtin_registry(), kUrdf, yaml) {}
  Reply set_state(const std::string& component, Lifecycle state) {
    std::optional<Reply> got;
    cm->set_component_state(component, state, [&](const Reply& r) { got = r; });
    for (int k = 0; k < 5 && !got; ++k) cycle();
    return got.value_or(Reply{false, "no reply"});
  }
  bool running(const std::string& name) {
    for (const auto& s : cm->loop().slots())
      if (s->name == name) return s->running;
    return false;
  }
  Lifecycle state_of(const std::string& component) {
    return cm->hardware().components()[size_t(cm->hardware().component_index(component))].state;
  }
  int actuator_index(const std::string& joint) {
    const auto& joints = cm->hardware().joints();
    for (size_t k = 0; k < joints.size(); ++k)
      if (joints[k].name == joint) return int(k);
    return -1;
  }
  void start_all() {
    for (const char* c : {"joint_state_broadcaster", "arm_controller", "gripper_controller"}) start(c);
  }
};

TEST(HardwareLifecycle, AComponentSetInactiveStopsTheControllersThatCommandItInThatCycle) {
  ArmRig rig;
  rig.start_all();
  rig.cycle(5);
  const Reply r = rig.set_state("arm", Lifecycle::Inactive);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "hardware component 'arm': active -> inactive (deactivate); stopped [arm_controller]"))
      << r.message;
  EXPECT_FALSE(rig.running("arm_controller"));
  EXPECT_TRUE(rig.running("gripper_controller")) << "the gripper is another component";
  EXPECT_TRUE(rig.running("joint_state_broadcaster")) << "an inactive component's states can still be read";
  EXPECT_EQ(rig.state_of("arm"), Lifecycle::Inactive);
  rig.cycle(3);
  const hardware_command_t& c = rig.commands.back();
  ASSERT_EQ(c.num_components, 3) << "every component listed while one is not active";
  EXPECT_EQ(c.component[0], "arm");
  EXPECT_EQ(c.component_state[0], hardware_command_t::COMPONENT_INACTIVE);
  EXPECT_EQ(c.component_state[1], hardware_command_t::COMPONENT_ACTIVE);
  EXPECT_EQ(c.mode[size_t(rig.actuator_index("shoulder"))], hardware_command_t::MODE_NONE);
  EXPECT_EQ(c.mode[size_t(rig.actuator_index("elbow"))], hardware_command_t::MODE_NONE);
  EXPECT_EQ(c.mode[size_t(rig.actuator_index("finger_joint"))], hardware_command_t::MODE_POSITION);

  // Back to active: the list goes, and the controller starts again.
  const Reply back = rig.set_state("arm", Lifecycle::Active);
  ASSERT_TRUE(back.ok) << back.message;
  EXPECT_TRUE(has(back.message, "inactive -> active (activate); stopped []")) << back.message;
  ASSERT_TRUE(rig.switch_({"arm_controller"}, {}).ok);
  rig.cycle(2);
  EXPECT_EQ(rig.commands.back().num_components, 0);
  EXPECT_EQ(rig.commands.back().mode[size_t(rig.actuator_index("shoulder"))], hardware_command_t::MODE_POSITION);
}

TEST(HardwareLifecycle, AnUnconfiguredComponentStopsItsReadersToo) {
  ArmRig rig;
  rig.start_all();
  const Reply r = rig.set_state("gripper", Lifecycle::Unconfigured);
  ASSERT_TRUE(r.ok) << r.message;
  EXPECT_TRUE(has(r.message, "active -> unconfigured (deactivate, cleanup)")) << r.message;
  EXPECT_FALSE(rig.running("gripper_controller"));
  EXPECT_FALSE(rig.running("joint_state_broadcaster")) << "it reads finger_joint's states";
  EXPECT_TRUE(rig.running("arm_controller"));
}

TEST(HardwareLifecycle, AControllerCannotStartOnAComponentThatIsNotActive) {
  ArmRig rig;
  rig.cycle();
  ASSERT_TRUE(rig.load("arm_controller").ok);
  ASSERT_TRUE(rig.set_state("arm", Lifecycle::Inactive).ok);
  const Reply r = rig.switch_({"arm_controller"}, {});
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "cannot start 'arm_controller': it commands hardware component 'arm', which is inactive; "
                             "activate it first: cmctl set-hardware-component-state arm active"))
      << r.message;
  EXPECT_FALSE(rig.running("arm_controller"));
}

TEST(HardwareLifecycle, UnknownComponentsAndFinalizedOnesAreRefusedNamingWhatThereIs) {
  ArmRig rig;
  rig.cycle();
  Reply r = rig.set_state("gripper_hw", Lifecycle::Inactive);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "there is none of that name in " + kUrdf + " (its components: arm, gripper, wrist)"))
      << r.message;
  ASSERT_TRUE(rig.set_state("wrist", Lifecycle::Finalized).ok);
  r = rig.set_state("wrist", Lifecycle::Active);
  EXPECT_FALSE(r.ok);
  EXPECT_TRUE(has(r.message, "it is finalized")) << r.message;
  r = rig.set_state("arm", Lifecycle::Active);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(has(r.message, "already active")) << r.message;
}

TEST(HardwareLifecycle, AComponentInErrorIsUnconfiguredAndItsControllersStopInTheCycleItArrives) {
  ArmRig rig;
  rig.start_all();
  rig.cycle(3);
  rig.state.error_component = {"gripper"};
  rig.state.error_reason = {"finger motor over current"};
  rig.state.num_component_errors = 1;
  const int64_t failing_step = rig.step;
  rig.cycle(1);
  EXPECT_FALSE(rig.running("gripper_controller"));
  EXPECT_FALSE(rig.running("joint_state_broadcaster")) << "the component's states are gone too (unconfigured)";
  EXPECT_TRUE(rig.running("arm_controller"));
  EXPECT_EQ(rig.state_of("gripper"), Lifecycle::Unconfigured);
  const hardware_command_t& c = rig.commands.back();
  EXPECT_EQ(c.step, failing_step);
  EXPECT_EQ(c.mode[size_t(rig.actuator_index("finger_joint"))], hardware_command_t::MODE_NONE)
      << "not commanded in the cycle the error came";
  EXPECT_EQ(c.component_state[1], hardware_command_t::COMPONENT_UNCONFIGURED) << "the hardware learns it at once";
  const auto listed = rig.cm->components();
  ASSERT_EQ(listed.size(), 3u);
  EXPECT_EQ(listed[1].state_label, "unconfigured");
  EXPECT_EQ(listed[1].error, "finger motor over current");
  // The hardware keeps reporting it until it sees the new state; that is the same error, not a new one.
  rig.cycle(2);
  rig.state.error_component.clear();
  rig.state.error_reason.clear();
  rig.state.num_component_errors = 0;
  rig.cycle(1);
  // Once activated again, the gripper's controller starts.
  const Reply back = rig.set_state("gripper", Lifecycle::Active);
  ASSERT_TRUE(back.ok) << back.message;
  EXPECT_TRUE(has(back.message, "its last error: finger motor over current")) << back.message;
  EXPECT_TRUE(rig.switch_({"gripper_controller", "joint_state_broadcaster"}, {}).ok);
  EXPECT_TRUE(rig.running("gripper_controller"));
}

TEST(HardwareLifecycle, TheParameterFileStartsComponentsUnconfiguredOrInactive) {
  const std::string dir = lt::temp_dir("lifecycle_initial");
  std::ifstream in(kYaml);
  std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  yaml.replace(yaml.find("    update_rate: 500\n"), 0,
               "    hardware_components_initial_state:\n      inactive: [gripper]\n");
  std::ofstream(dir + "/arm.yaml") << yaml;
  ArmRig rig(dir + "/arm.yaml");
  EXPECT_EQ(rig.state_of("gripper"), Lifecycle::Inactive);
  rig.cycle();
  ASSERT_TRUE(rig.load("gripper_controller").ok);
  EXPECT_FALSE(rig.switch_({"gripper_controller"}, {}).ok);
  EXPECT_EQ(rig.commands.back().component_state[1], hardware_command_t::COMPONENT_INACTIVE);
  ASSERT_TRUE(rig.set_state("gripper", Lifecycle::Active).ok);
  EXPECT_TRUE(rig.switch_({"gripper_controller"}, {}).ok);
}

TEST(HardwareLifecycle, NoAllocationOnTheLoopPathWhileAComponentIsNotActive) {
  ArmRig rig;
  rig.start_all();
  ASSERT_TRUE(rig.set_state("gripper", Lifecycle::Inactive).ok);
  rig.cycle(5);
  rig.commands.reserve(rig.commands.size() + 200);
  EXPECT_EQ(rig.allocations_in_cycles(100, false, false), 0);
  EXPECT_EQ(rig.cm->last_command().num_components, 3);
}

}  // namespace
