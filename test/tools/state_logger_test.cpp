// state-logger on a private LCM URL: columns, row counts, several channels,
// text columns, and the rows written before a Ctrl-C are all on disk.
#include <gtest/gtest.h>

#include <filesystem>

#include "lcm_control/controller_state_t.hpp"
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
// Up to 40 joint_states (state(k)) at 200 Hz while the logger runs.
void publish_states(const std::string& url, ChildProcess& logger) {
  lcm::LCM lc(url);
  for (int k = 0; k < 40 && logger.running(); ++k) {
    const joint_state_t js = state(k);
    lc.publish("joint_states", &js);
    pump_until(lc, [] { return false; }, 0.005);
  }
}

}  // namespace

TEST(StateLogger, JointStatesToCsvWithCount) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("logger");
  ChildProcess p({bin("state-logger"), "--output", dir + "/js.csv", "--count", "25", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("logging joint_states", 5.0)) << p.output();
  publish_states(url, p);
  ASSERT_EQ(p.wait(5.0), 0) << p.output();
  const Csv csv = read_csv(dir + "/js.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"utime", "position[0]", "position[1]", "velocity[0]", "velocity[1]",
                                                 "effort[0]", "effort[1]", "name[0]", "name[1]"}));
  ASSERT_EQ(csv.rows.size(), 25u);
  for (int k = 0; k < 25; ++k) {
    EXPECT_EQ(csv.rows[k][0], std::to_string(1000 * k));
    EXPECT_DOUBLE_EQ(std::stod(csv.rows[k][2]), -0.25 * k);
    EXPECT_EQ(csv.rows[k][8], "j2");
  }
  EXPECT_NE(p.output().find("joint_states: 25 rows, 9 columns"), std::string::npos) << p.output();
}

TEST(StateLogger, TakesTheRosStyleChannelName) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("logger_slash");
  ChildProcess p({bin("state-logger"), "/joint_states", "--output", dir + "/js.csv", "--count", "5", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("logging joint_states", 5.0)) << p.output();
  publish_states(url, p);
  ASSERT_EQ(p.wait(5.0), 0) << p.output();
  EXPECT_EQ(read_csv(dir + "/js.csv").rows.size(), 5u);
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

TEST(StateLogger, KeepsTheControllersTextInQuotedColumns) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("logger_text");
  ChildProcess p({bin("state-logger"), "arm_controller/status", "j2_controller/state", "--output-dir", dir, "--count",
                  "3", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("logging j2_controller/state", 5.0)) << p.output();
  lcm::LCM lc(url);
  for (int k = 0; k < 20 && p.running(); ++k) {
    const trajectory_status_t s = trajectory_status(k % 3);
    lc.publish("arm_controller/status", &s);
    controller_state_t c{};
    c.utime = k;
    c.controller = "j2_controller";
    c.joint = "j2";
    c.error = 0.5 * k;
    lc.publish("j2_controller/state", &c);
    pump_until(lc, [] { return false; }, 0.005);
  }
  ASSERT_EQ(p.wait(5.0), 0) << p.output();

  const Csv status = read_csv(dir + "/arm_controller__status.csv");
  EXPECT_EQ(status.header, (std::vector<std::string>{"utime", "goal_id", "status", "desired[0]", "actual[0]",
                                                     "error[0]", "message", "joint_names[0]"}));
  ASSERT_EQ(status.rows.size(), 3u);
  EXPECT_EQ(status.rows[0][6], "");
  EXPECT_EQ(status.rows[1][6], kGoalToleranceText);
  EXPECT_EQ(status.rows[1][5], "0.5");
  EXPECT_EQ(status.rows[2][6], kRejectedText);
  EXPECT_EQ(status.rows[2][7], "j1");
  EXPECT_NE(read_text(dir + "/arm_controller__status.csv")
                .find(",\"goal 3 rejected: joint \"\"j3\"\" is not controlled\nknown joints: j1, j2\",j1\n"),
            std::string::npos);

  const Csv state = read_csv(dir + "/j2_controller__state.csv");
  ASSERT_EQ(state.rows.size(), 3u);
  const int controller = state.column("controller"), joint = state.column("joint"), error = state.column("error");
  ASSERT_EQ(controller, int(state.header.size()) - 2);
  ASSERT_EQ(joint, int(state.header.size()) - 1);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(state.rows[k][size_t(controller)], "j2_controller");
    EXPECT_EQ(state.rows[k][size_t(joint)], "j2");
    EXPECT_DOUBLE_EQ(std::stod(state.rows[k][size_t(error)]), 0.5 * std::stod(state.rows[k][0]));
  }
}

TEST(StateLogger, DurationBoundsAQuietBus) {
  const std::string dir = temp_dir("logger_quiet");
  ChildProcess p({bin("state-logger"), "--output", dir + "/js.csv", "--duration", "0.3", "--lcm-url",
                  unique_lcm_url()});
  EXPECT_EQ(p.wait(5.0), 4) << p.output();  // no answer on the bus
  EXPECT_NE(p.output().find("joint_states: no messages"), std::string::npos) << p.output();
  EXPECT_NE(p.output().find("state-logger: error: no messages on joint_states (udpm://"), std::string::npos)
      << p.output();
  EXPECT_NE(p.output().find("channels seen: none. Check the channel name, --namespace and --lcm-url"),
            std::string::npos)
      << p.output();
}
