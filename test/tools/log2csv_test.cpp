// log2csv on logs written with lcm::LogFile and recorded by lcm-logger.
#include <gtest/gtest.h>

#include <filesystem>

#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

TEST(Log2Csv, OneCsvPerChannelOfOurTypesAndSaysWhatItSkipped) {
  const std::string dir = temp_dir("log2csv");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess p({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir + "/csv"});
  ASSERT_EQ(p.wait(10.0), 0) << p.output();
  const std::string out = p.output();

  const Csv js = read_csv(dir + "/csv/joint_states.csv");
  EXPECT_EQ(js.header, (std::vector<std::string>{"utime", "position[0]", "position[1]", "velocity[0]", "velocity[1]",
                                                 "effort[0]", "effort[1]", "name[0]", "name[1]"}));
  ASSERT_EQ(js.rows.size(), 50u);
  EXPECT_EQ(js.rows[7][0], "70000");
  EXPECT_DOUBLE_EQ(std::stod(js.rows[7][2]), std::sin(0.7));
  EXPECT_EQ(js.rows[49][5], "49");
  EXPECT_EQ(js.rows[49][7], "j1");

  const Csv cmd = read_csv(dir + "/csv/j2_controller__command.csv");
  EXPECT_EQ(cmd.header, (std::vector<std::string>{"utime", "data"}));
  EXPECT_EQ(cmd.rows.size(), 20u);

  EXPECT_FALSE(std::filesystem::exists(dir + "/csv/controller_manager__response.csv"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/csv/other_robot__blob.csv"));
  EXPECT_NE(out.find("skipped controller_manager/response: lcm_control.cm_response_t: controller-manager answer"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("skipped other_robot/blob: not an lcm_control type"), std::string::npos) << out;
  EXPECT_NE(out.find("joint_states.csv: 50 rows, 9 columns"), std::string::npos) << out;
}

TEST(Log2Csv, KeepsAFailureMessageInAQuotedColumn) {
  const std::string dir = temp_dir("log2csv_text");
  write_status_log(dir + "/run.lcmlog");
  ChildProcess p({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir});
  ASSERT_EQ(p.wait(10.0), 0) << p.output();
  EXPECT_NE(p.output().find("arm_controller__status.csv: 3 rows, 8 columns (lcm_control.trajectory_status_t"),
            std::string::npos)
      << p.output();

  const std::string path = dir + "/arm_controller__status.csv";
  const Csv csv = read_csv(path);
  EXPECT_EQ(csv.header, (std::vector<std::string>{"utime", "goal_id", "status", "desired[0]", "actual[0]", "error[0]",
                                                  "message", "joint_names[0]"}));
  ASSERT_EQ(csv.rows.size(), 3u);
  EXPECT_EQ(csv.rows[0], (std::vector<std::string>{"0", "1", "0", "1", "1", "0", "", "j1"}));
  EXPECT_EQ(csv.rows[1], (std::vector<std::string>{"10000", "2", "4", "1", "0.5", "0.5", kGoalToleranceText, "j1"}));
  EXPECT_EQ(csv.rows[2], (std::vector<std::string>{"20000", "3", "2", "1", "0", "1", kRejectedText, "j1"}));
  const std::string raw = read_text(path);
  EXPECT_NE(raw.find("\n10000,2,4,1,0.5,0.5,\"goal tolerance violated on joint 'j1': error 0.500000 (tolerance "
                     "0.100000), velocity 0.000000 (stopped tolerance 0.010000), 0.250 s after the trajectory end "
                     "(goal_time 0.200)\",j1\n"),
            std::string::npos)
      << raw;
}

TEST(Log2Csv, ChannelFilterAndLogTime) {
  const std::string dir = temp_dir("log2csv_filter");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess p({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir, "--channel", "j2_.*", "--log-time"});
  ASSERT_EQ(p.wait(10.0), 0) << p.output();
  EXPECT_FALSE(std::filesystem::exists(dir + "/joint_states.csv"));
  const Csv cmd = read_csv(dir + "/j2_controller__command.csv");
  EXPECT_EQ(cmd.header, (std::vector<std::string>{"log_utime", "utime", "data"}));
  ASSERT_EQ(cmd.rows.size(), 20u);
  EXPECT_EQ(cmd.rows[1][0], "1025000");

  const std::string ros = temp_dir("log2csv_filter_ros");  // ROS's leading slash
  ChildProcess q({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", ros, "--channel", "/joint_states"});
  ASSERT_EQ(q.wait(10.0), 0) << q.output();
  EXPECT_TRUE(std::filesystem::exists(ros + "/joint_states.csv")) << q.output();
  EXPECT_FALSE(std::filesystem::exists(ros + "/j2_controller__command.csv"));
}

TEST(Log2Csv, FieldsByPathOrDashboardLabelAndTheNearestForATypo) {
  const std::string dir = temp_dir("log2csv_fields");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess p({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir, "-c", "joint_states", "--field",
                  "position[j2]", "--field", "velocity"});
  ASSERT_EQ(p.wait(10.0), 0) << p.output();
  const Csv js = read_csv(dir + "/joint_states.csv");
  EXPECT_EQ(js.header, (std::vector<std::string>{"utime", "position[1]", "velocity[0]", "velocity[1]"}));
  ASSERT_EQ(js.rows.size(), 50u);
  EXPECT_EQ(js.rows[10][2], "0.5");

  ChildProcess typo({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir, "--field", "postion[j2]"});
  EXPECT_EQ(typo.wait(10.0), 1) << typo.output();
  EXPECT_NE(typo.output().find("log2csv: error: " + dir + "/run.lcmlog: no column of these names in any channel "
                               "read:\n  --field postion[j2]: nearest in joint_states: position[j2], position[j1], "
                               "position[0], position[1], position\n"),
            std::string::npos)
      << typo.output();
}

TEST(Log2Csv, FailuresSayWhat) {
  const std::string dir = temp_dir("log2csv_fail");
  ChildProcess missing({bin("log2csv"), dir + "/nope.lcmlog"});
  EXPECT_EQ(missing.wait(10.0), 3);  // a bad input file
  EXPECT_NE(missing.output().find("log2csv: error: " + dir + "/nope.lcmlog: cannot read the log: No such file"),
            std::string::npos)
      << missing.output();
  write_test_log(dir + "/run.lcmlog");
  ChildProcess none({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir, "--channel", "nothing"});
  EXPECT_EQ(none.wait(10.0), 1);
  EXPECT_NE(none.output().find("no channel of lcm_control types matching --channel"), std::string::npos)
      << none.output();
}

// lcm-logger records what turret-cmd-like publishers send; log2csv reads it back.
TEST(Log2Csv, ReadsWhatLcmLoggerRecorded) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("log2csv_logger");
  const std::string log_path = dir + "/rec.lcmlog";
  ChildProcess logger({"/usr/bin/lcm-logger", "--lcm-url=" + url, "-f", log_path});
  lcm::LCM lc(url);
  // Publish on a warm-up channel until the logger has written something.
  joint_state_t js{};
  js.num_joints = 1;
  js.name = {"j"};
  js.position = {0};
  js.velocity = {0};
  js.effort = {0};
  for (int k = 0; k < 250; ++k) {
    lc.publish("warmup", &js);
    std::error_code ec;
    if (std::filesystem::file_size(log_path, ec) > 0 && !ec) break;
    pump_until(lc, [] { return false; }, 0.02);
  }
  ASSERT_GT(std::filesystem::file_size(log_path), 0u) << logger.output();
  for (int k = 0; k < 30; ++k) {
    js.utime = k;
    js.position = {0.1 * k};
    lc.publish("joint_states", &js);
    pump_until(lc, [] { return false; }, 0.002);
  }
  pump_until(lc, [] { return false; }, 0.3);
  EXPECT_EQ(logger.stop(5.0), 0) << logger.output();
  ChildProcess conv({bin("log2csv"), log_path, "--output-dir", dir, "--channel", "joint_states"});
  ASSERT_EQ(conv.wait(10.0), 0) << conv.output();
  const Csv csv = read_csv(dir + "/joint_states.csv");
  EXPECT_EQ(csv.header, (std::vector<std::string>{"utime", "position[0]", "velocity[0]", "effort[0]", "name[0]"}));
  ASSERT_EQ(csv.rows.size(), 30u);
  EXPECT_EQ(csv.rows[29][0], "29");
  EXPECT_DOUBLE_EQ(std::stod(csv.rows[29][1]), 0.1 * 29);
}
