// state-logger on a private LCM URL: columns, row counts, several channels,
// and the rows written before a Ctrl-C are all on disk.
#include <gtest/gtest.h>

#include <filesystem>

#include "lcm_control/float64_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

namespace {
joint_state_t state(int k) {
  joint_state_t js{};
  js.utime = 1000 * k;
  js.num_joints = 2;
  js.name = {"j1", "j2"};
  js.position = {0.5 * k, -0.25 * k};
  js.velocity = {1, 2};
  js.effort = {3, 4};
  return js;
}
}  // namespace

TEST(StateLogger, JointStatesToCsvWithCount) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("logger");
  ChildProcess p({bin("state-logger"), "--output", dir + "/js.csv", "--count", "25", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("logging joint_states", 5.0)) << p.output();
  lcm::LCM lc(url);
  for (int k = 0; k < 40 && p.running(); ++k) {
    const joint_state_t js = state(k);
    lc.publish("joint_states", &js);
    pump_until(lc, [] { return false; }, 0.005);
  }
  ASSERT_EQ(p.wait(5.0), 0) << p.output();
  const Csv csv = read_csv(dir + "/js.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"utime", "position[0]", "position[1]", "velocity[0]", "velocity[1]",
                                                 "effort[0]", "effort[1]"}));
  ASSERT_EQ(csv.rows.size(), 25u);
  for (int k = 0; k < 25; ++k) {
    EXPECT_EQ(csv.rows[k][0], std::to_string(1000 * k));
    EXPECT_DOUBLE_EQ(std::stod(csv.rows[k][2]), -0.25 * k);
  }
  EXPECT_NE(p.output().find("joint_states: 25 rows, 7 columns"), std::string::npos) << p.output();
}

TEST(StateLogger, EveryRowIsOnDiskAfterCtrlC) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("logger_int");
  ChildProcess p({bin("state-logger"), "--output", dir + "/js.csv", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("logging joint_states", 5.0)) << p.output();
  lcm::LCM lc(url);
  for (int k = 0; k < 17; ++k) {
    const joint_state_t js = state(k);
    lc.publish("joint_states", &js);
    pump_until(lc, [] { return false; }, 0.003);
  }
  pump_until(lc, [] { return false; }, 0.2);
  EXPECT_EQ(p.stop(5.0, SIGINT), 0) << p.output();
  EXPECT_EQ(read_csv(dir + "/js.csv").rows.size(), 17u);
}

TEST(StateLogger, SeveralChannelsOneFileEachWithNamespace) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("logger_multi");
  ChildProcess p({bin("state-logger"), "joint_states", "j2_controller/command", "--output-dir", dir, "--count", "5",
                  "--namespace", "r1", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("logging r1/j2_controller/command", 5.0)) << p.output();
  lcm::LCM lc(url);
  for (int k = 0; k < 20 && p.running(); ++k) {
    const joint_state_t js = state(k);
    lc.publish("r1/joint_states", &js);
    lc.publish("joint_states", &js);  // another robot's: not logged
    float64_t c{};
    c.utime = k;
    c.data = 2.0 * k;
    lc.publish("r1/j2_controller/command", &c);
    pump_until(lc, [] { return false; }, 0.005);
  }
  ASSERT_EQ(p.wait(5.0), 0) << p.output();
  EXPECT_EQ(read_csv(dir + "/r1__joint_states.csv").rows.size(), 5u);
  const Csv cmd = read_csv(dir + "/r1__j2_controller__command.csv");
  EXPECT_EQ(cmd.header, (std::vector<std::string>{"utime", "data"}));
  ASSERT_EQ(cmd.rows.size(), 5u);
  EXPECT_EQ(cmd.rows[4][1], "8");
}

TEST(StateLogger, DurationBoundsAQuietBus) {
  const std::string dir = temp_dir("logger_quiet");
  ChildProcess p({bin("state-logger"), "--output", dir + "/js.csv", "--duration", "0.3", "--lcm-url",
                  unique_lcm_url()});
  EXPECT_EQ(p.wait(5.0), 0) << p.output();
  EXPECT_NE(p.output().find("joint_states: no messages"), std::string::npos) << p.output();
}
