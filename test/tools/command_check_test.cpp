// The check every publishing tool makes before it commands a controller: the type its command channel takes, the
// width of a group controller's command, what to use instead, and the hardware's cause of a failed goal.
#include "tools/lib/clients/command_check.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace lcm_control;
using namespace lcm_control::tools;

namespace {

controller_info_t info(std::string name, std::string type, std::string command_type, std::string channel, int width) {
  controller_info_t c{};
  c.name = std::move(name);
  c.type = std::move(type);
  c.state = "running";
  c.joints = {"j1", "j2"};
  c.num_joints = 2;
  c.command_type = std::move(command_type);
  c.command_channel = std::move(channel);
  c.command_width = width;
  c.command_quantity = width > 0 ? "position" : "";
  return c;
}

const std::vector<controller_info_t> kListed = {
    info("arm", "position_controllers/JointTrajectoryController", "joint_trajectory_t", "command", 0),
    info("group", "position_controllers/JointGroupPositionController", "float64_array_t", "command", 2),
    info("j1_controller", "position_controllers/JointPositionController", "float64_t", "command", 1),
    info("base", "diff_drive_controller/DiffDriveController", "twist_t", "cmd_vel", 0),
    info("hand", "position_controllers/GripperActionController", "gripper_command_t", "command", 0)};

}  // namespace

TEST(CommandCheck, AMismatchNamesBothTypesTheChannelAndTheToolToUse) {
  EXPECT_EQ(type_mismatch(kListed[0], {"joint_trajectory_t", 0}, "command"), "");
  EXPECT_EQ(type_mismatch(kListed[0], {"float64_t", 0}, "command", "r1/"),
            "arm takes joint_trajectory_t on r1/arm/command; float64_t was given: use send-trajectory arm ...");
  EXPECT_EQ(type_mismatch(kListed[1], {"float64_t", 0}, "command"),
            "group takes float64_array_t on group/command; float64_t was given: use turret-cmd group V1 V2");
  EXPECT_EQ(type_mismatch(kListed[1], {"float64_array_t", 3}, "command"),
            "group takes float64_array_t of 2 numbers on group/command (one position per joint: j1, j2); 3 were "
            "given: use turret-cmd group V1 V2");
  EXPECT_EQ(type_mismatch(kListed[1], {"float64_array_t", 2}, "command"), "");
  EXPECT_EQ(type_mismatch(kListed[2], {"twist_t", 0}, "cmd_vel"),
            "j1_controller takes float64_t on j1_controller/command; twist_t was given on j1_controller/cmd_vel: use "
            "turret-cmd j1_controller VALUE");
  EXPECT_EQ(type_mismatch(kListed[3], {"float64_t", 0}, "command"),
            "base takes twist_t on base/cmd_vel; float64_t was given on base/command: use drive base LINEAR ANGULAR");
  EXPECT_EQ(type_mismatch(kListed[4], {"joint_trajectory_t", 0}, "command"),
            "hand takes gripper_command_t on hand/command; joint_trajectory_t was given: use gripper hand --position P");
  controller_info_t own = info("mine", "my_controllers/Mine", "my_command_t", "goal", 0);
  EXPECT_EQ(type_mismatch(own, {"float64_t", 0}, "goal"),
            "mine takes my_command_t on mine/goal; float64_t was given: use bus pub mine/goal my_command_t "
            "FIELD=VALUE...");
}

TEST(CommandCheck, CommandableRefusesAStoppedControllerAndNamesTheClosestMissingOne) {
  std::vector<controller_info_t> listed = kListed;
  listed[0].state = "stopped";
  auto error_of = [&](const std::string& name, const Sent& sent) {
    try {
      commandable(listed, name, sent, "(from the YAML)");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of("arm", {"joint_trajectory_t", 0}),
            "'arm' is loaded but stopped, not running: start it with `cmctl start arm`");
  EXPECT_EQ(error_of("arm", {"float64_t", 0}),
            "arm takes joint_trajectory_t on arm/command; float64_t was given: use send-trajectory arm ...");
  EXPECT_EQ(error_of("hnad", {"gripper_command_t", 0}),
            "no controller 'hnad' in the controller manager (loaded: arm, group, j1_controller, base, hand): load and "
            "start it with `spawner hnad` (from the YAML); did you mean 'hand'?");
  EXPECT_EQ(error_of("hand", {"gripper_command_t", 0}), "");
}

TEST(CommandCheck, AChannelIsAControllersOnlyWhenItIsItsCommandChannel) {
  std::string rest;
  ASSERT_NE(controller_on(kListed, "base/cmd_vel", &rest), nullptr);
  EXPECT_EQ(controller_on(kListed, "base/cmd_vel")->name, "base");
  EXPECT_EQ(rest, "cmd_vel");
  EXPECT_EQ(controller_on(kListed, "arm/command")->name, "arm");
  EXPECT_EQ(controller_on(kListed, "arm/state"), nullptr);
  EXPECT_EQ(controller_on(kListed, "other/command"), nullptr);
  EXPECT_EQ(controller_on(kListed, "arm"), nullptr);
}

TEST(CommandCheck, TheHardwareLineNamesTheEStopAPauseOrSilence) {
  cm_response_t r{};
  r.hardware = "session 3f, lockstep, 1000 Hz, 1.00x real time, step 12, last state 0.001 s ago";
  EXPECT_FALSE(hardware_cause(r).has_value());
  r.hardware += "; e-stop engaged: the hardware holds still";
  ASSERT_TRUE(hardware_cause(r).has_value());
  EXPECT_EQ(hardware_cause(r)->rfind("the e-stop is engaged", 0), 0u);
  r.hardware = "session 3f, real time, step 12, last state 0.1 s ago; step 12 repeated for 2.0 s: the hardware is "
               "paused (cmctl resume)";
  EXPECT_EQ(hardware_cause(r)->rfind("the simulator is paused", 0), 0u);
  r.hardware = "session 3f, real time, step 12, last state 3.0 s ago; SILENT for 3.0 s: controllers are not updated";
  EXPECT_EQ(hardware_cause(r)->rfind("the hardware is silent", 0), 0u);
}

// ROS 2 users write topics as ROS 2 names them: a leading '/', `<c>/commands` (forward command controllers),
// `<c>/joint_trajectory` (the JTC's topic); each is the controller's own command channel here, said in a note.
// Actions and private names are refused with the tool to use.
TEST(CommandCheck, Ros2TopicNamesAreTheControllersCommandChannels) {
  const std::vector<controller_info_t> listed = {
      kListed[0], kListed[1], kListed[3],
      info("gpio", "gpio_controllers/GpioCommandController", "interface_group_values_t", "commands", 0)};
  std::string note;
  EXPECT_EQ(channel_from_ros("/group/commands", &listed, &note), "group/command");
  EXPECT_EQ(note, "'/group/commands' is ROS 2's name; here the channel is 'group/command' (relative to --namespace)");
  EXPECT_EQ(channel_from_ros("/arm/joint_trajectory", &listed, &note), "arm/command");
  EXPECT_EQ(channel_from_ros("gpio/commands", &listed, &note), "gpio/commands") << "its channel is ROS 2's";
  EXPECT_EQ(note, "");
  EXPECT_EQ(channel_from_ros("/cmd_vel", &listed, &note), "cmd_vel");
  EXPECT_EQ(channel_from_ros("base/cmd_vel", &listed, &note), "base/cmd_vel");
  EXPECT_EQ(note, "");
  EXPECT_EQ(channel_from_ros("/other/commands", nullptr, &note), "other/command") << "no list: the usual channel";
  for (const auto& [name, tool] : {std::pair{"/arm/follow_joint_trajectory", "send-trajectory arm --point"},
                                   std::pair{"/hand/gripper_cmd", "gripper hand --position"},
                                   std::pair{"~/commands", "CONTROLLER/command"}}) {
    try {
      channel_from_ros(name, &listed, &note);
      ADD_FAILURE() << name << " accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(tool), std::string::npos) << e.what();
    }
  }
}
