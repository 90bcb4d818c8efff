// <gpio> interfaces end to end (test/robots/gpio_arm.urdf, two <gpio> blocks as ros2_control_demos' example 10 has
// them): gpio_controllers/GpioCommandController publishes the states, a command on an output reads back on its state
// interface one cycle later, on mock hardware and in Bullet (--physics) alike; a vacuum state starts at its
// initial_value.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>

#include "bus/bus.hpp"
#include "lcm_control/interface_group_values_t.hpp"
#include "test/e2e/session.hpp"
#include "test/support/lcm_test.hpp"

namespace lcm_control::testing {
namespace {

// "<gpio>/<interface>" -> value, from a gpio_states message.
std::map<std::string, double> values_of(const interface_group_values_t& m) {
  std::map<std::string, double> out;
  for (int g = 0; g < m.num_groups; ++g)
    for (int i = 0; i < m.interface_values[size_t(g)].num_interfaces; ++i)
      out[m.interface_groups[size_t(g)] + "/" + m.interface_values[size_t(g)].interface_names[size_t(i)]] =
          m.interface_values[size_t(g)].values[size_t(i)];
  return out;
}

interface_group_values_t command(const std::string& gpio, const std::string& iface, double value) {
  interface_group_values_t c{};
  c.num_groups = 1;
  c.interface_groups = {gpio};
  interface_values_t v{};
  v.num_interfaces = 1;
  v.interface_names = {iface};
  v.values = {value};
  c.interface_values = {v};
  return c;
}

// Commands 0.27 on flange_vacuum/vacuum and 0.5 on flange_analog_IOs/analog_output1 through the GPIO controller, and
// waits (at most timeout_s) for both to read back on their state interfaces; `v`: the last states seen.
::testing::AssertionResult outputs_read_back(Bus& bus, const Recorder<interface_group_values_t>& states,
                                             std::map<std::string, double>& v, double timeout_s) {
  const interface_group_values_t vacuum = command("flange_vacuum", "vacuum", 0.27);
  const interface_group_values_t analog = command("flange_analog_IOs", "analog_output1", 0.5);
  bus.lcm().publish("gpio_controller/commands", &vacuum);
  bus.lcm().publish("gpio_controller/commands", &analog);
  if (pump_until(bus.lcm(), [&] {
        v = values_of(states.messages.back());
        return v["flange_vacuum/vacuum"] == 0.27 && v["flange_analog_IOs/analog_output1"] == 0.5;
      }, timeout_s))
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "vacuum " << v["flange_vacuum/vacuum"] << ", analog_output1 "
                                       << v["flange_analog_IOs/analog_output1"];
}

void commands_read_back(const std::vector<std::string>& sim_flags) {
  RobotSession robot(source("test/robots/gpio_arm.urdf"), source("test/robots/gpio_arm.yaml"));
  Bus bus(robot.url(), "");
  Recorder<interface_group_values_t> states(bus.lcm(), "gpio_controller/gpio_states");
  robot.start_controller_manager();
  ASSERT_NO_FATAL_FAILURE(robot.start_sim(sim_flags, 20));
  ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_broadcaster", "gpio_controller", "forward_position_controller"}));
  ASSERT_TRUE(pump_until(bus.lcm(), [&] { return !states.messages.empty(); }, 5)) << robot.cm_output();
  std::map<std::string, double> v = values_of(states.messages.back());
  EXPECT_EQ(v.size(), 4u) << "every state interface of both gpios";
  EXPECT_EQ(v["flange_vacuum/vacuum"], 1.0) << "its initial_value";
  EXPECT_EQ(v["flange_analog_IOs/analog_output1"], 0.0);
  ASSERT_TRUE(outputs_read_back(bus, states, v, 5));
  EXPECT_EQ(v["flange_analog_IOs/analog_input1"], 0.0) << "an input nobody commands keeps its value";
  // An interface it does not command is dropped, named, and changes nothing.
  const interface_group_values_t wrong = command("flange_analog_IOs", "analog_input1", 3.0);
  bus.lcm().publish("gpio_controller/commands", &wrong);
  pump_until(bus.lcm(), [] { return false; }, 0.3);
  EXPECT_EQ(values_of(states.messages.back())["flange_analog_IOs/analog_input1"], 0.0);
  EXPECT_NE(robot.cm_output().find("'flange_analog_IOs/analog_input1' is not one of its command interfaces "
                                   "(flange_analog_IOs/analog_output1, flange_vacuum/vacuum)"),
            std::string::npos)
      << robot.cm_output();
}

TEST(Gpio, ACommandOnAGpioOutputReadsBackOnItsStateOnMockHardware) { commands_read_back({}); }

TEST(Gpio, ACommandOnAGpioOutputReadsBackOnItsStateInBullet) { commands_read_back({"--physics"}); }

}  // namespace
}  // namespace lcm_control::testing

namespace lcm_control::testing {
namespace {

// ros2_control_demos' example 10 (../shared/ros2_robots/demo_gpio) with its own xacro and YAML, as its launch file
// runs it: its GPIO controller's command on an output reads back on the state interface.
TEST(Gpio, Ros2ControlDemosExample10RunsItsGpioController) {
  NEED_ROS2_ROBOTS(dir);
  const std::string pkg = dir + "/demo_gpio/pkgs/ros2_control_demo_example_10";
  LockstepSession robot(pkg + "/urdf/rrbot.urdf.xacro", pkg + "/config/rrbot_controllers.yaml",
                        {"--package-path", dir + "/demo_gpio/pkgs"});
  Bus bus(robot.url(), "");
  Recorder<interface_group_values_t> states(bus.lcm(), "gpio_controller/gpio_states");
  ASSERT_NO_FATAL_FAILURE(robot.start({"joint_state_broadcaster", "forward_position_controller", "gpio_controller"}));
  ASSERT_TRUE(pump_until(bus.lcm(), [&] { return !states.messages.empty(); }, 10)) << robot.cm_output();
  std::map<std::string, double> v = values_of(states.messages.back());
  EXPECT_EQ(v["flange_vacuum/vacuum"], 1.0) << "its initial_value";
  ASSERT_TRUE(outputs_read_back(bus, states, v, 10)) << robot.cm_output() << robot.sim_output();
  std::printf("example 10: vacuum 0.27 and analog_output1 0.5 read back on their state interfaces\n");
}

}  // namespace
}  // namespace lcm_control::testing
