// plotter: the PNG exists and the data it fed gnuplot matches log2csv's CSV.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "lcm_control/joint_state_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

namespace {
// Blocks of "t value" lines, one per path, as the plotter's --data file holds them.
std::vector<std::vector<std::pair<double, double>>> read_blocks(const std::string& path) {
  std::vector<std::vector<std::pair<double, double>>> blocks;
  std::ifstream in(path);
  std::string line;
  bool new_block = true;
  while (std::getline(in, line)) {
    if (line.empty()) {
      new_block = true;
      continue;
    }
    if (line[0] == '#') continue;
    if (new_block) blocks.emplace_back();
    new_block = false;
    const auto cells = split(line, ' ');
    blocks.back().emplace_back(std::stod(cells.at(0)), std::stod(cells.at(1)));
  }
  return blocks;
}
}  // namespace

TEST(Plotter, PngFromALogWhoseDataMatchesTheCsv) {
  const std::string dir = temp_dir("plotter");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess conv({bin("log2csv"), dir + "/run.lcmlog", "--output-dir", dir});
  ASSERT_EQ(conv.wait(10.0), 0) << conv.output();
  ChildProcess p({bin("plotter"), "joint_states.velocity[1]", "j2_controller/command.data", "--log",
                  dir + "/run.lcmlog", "--output", dir + "/plot.png", "--data", dir + "/plot.dat"});
  ASSERT_EQ(p.wait(30.0), 0) << p.output();

  const std::string png = read_text(dir + "/plot.png");
  ASSERT_GT(png.size(), 1000u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));

  const auto blocks = read_blocks(dir + "/plot.dat");
  ASSERT_EQ(blocks.size(), 2u);
  const Csv js = read_csv(dir + "/joint_states.csv");
  const Csv cmd = read_csv(dir + "/j2_controller__command.csv");
  ASSERT_EQ(blocks[0].size(), js.rows.size());
  ASSERT_EQ(blocks[1].size(), cmd.rows.size());
  const int vel1 = js.column("velocity[1]"), data = cmd.column("data");
  for (size_t k = 0; k < js.rows.size(); ++k) {
    EXPECT_DOUBLE_EQ(blocks[0][k].second, std::stod(js.rows[k][vel1])) << k;
    EXPECT_NEAR(blocks[0][k].first, 0.01 * double(k), 1e-9) << k;  // log time from the first message
  }
  for (size_t k = 0; k < cmd.rows.size(); ++k) {
    EXPECT_DOUBLE_EQ(blocks[1][k].second, std::stod(cmd.rows[k][data])) << k;
    EXPECT_NEAR(blocks[1][k].first, 0.02 * double(k) + 0.005, 1e-9) << k;
  }
}

TEST(Plotter, RosStylePathsSvgAndMessageTime) {
  const std::string dir = temp_dir("plotter_ros");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess p({bin("plotter"), "/j2_controller/command", "/joint_states/position[0]", "--log", dir + "/run.lcmlog",
                  "--output", dir + "/plot.svg", "--data", dir + "/plot.dat", "--time", "utime"});
  ASSERT_EQ(p.wait(30.0), 0) << p.output();
  EXPECT_NE(read_text(dir + "/plot.svg").find("<svg"), std::string::npos);
  const auto blocks = read_blocks(dir + "/plot.dat");
  ASSERT_EQ(blocks.size(), 2u);
  EXPECT_EQ(blocks[0].size(), 20u);
  EXPECT_NEAR(blocks[0][3].first, 0.065, 1e-9);  // utime 65000 us, first utime 0
  EXPECT_NEAR(blocks[1][3].second, 0.03, 1e-12);
}

// Units from the schema: on the y axis when the series share one, else in the legend; in a text plot each
// legend entry has a line of its own.
TEST(Plotter, UnitsOnTheAxisOrInTheLegend) {
  const std::string dir = temp_dir("plotter_units");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess same({bin("plotter"), "joint_states/position[0]", "joint_states/position[1]", "--log",
                     dir + "/run.lcmlog", "--output", dir + "/same.svg"});
  ASSERT_EQ(same.wait(30.0), 0) << same.output();
  const std::string svg = read_text(dir + "/same.svg");
  EXPECT_NE(svg.find("[rad or m]"), std::string::npos) << "y axis label";
  EXPECT_NE(svg.find("joint_states/position[1] [rad or m]"), std::string::npos);

  ChildProcess mixed({bin("plotter"), "/j2_controller/command", "joint_states/position[0]", "joint_states/velocity[1]",
                      "--log", dir + "/run.lcmlog", "--output", dir + "/mixed.svg", "--terminal"});
  ASSERT_EQ(mixed.wait(30.0), 0) << mixed.output();
  const std::string mixed_svg = read_text(dir + "/mixed.svg");
  EXPECT_NE(mixed_svg.find("value (units in the legend)"), std::string::npos);
  EXPECT_NE(mixed_svg.find("joint_states/velocity[1] [rad/s or m/s]"), std::string::npos);
  EXPECT_NE(mixed_svg.find("/j2_controller/command<"), std::string::npos) << "no unit: float64_t.data has none";
  const std::string out = mixed.output();
  const std::vector<std::string> entries = {"/j2_controller/command", "joint_states/position[0] [rad or m]",
                                            "joint_states/velocity[1] [rad/s or m/s]"};
  for (const auto& line : split(out, '\n')) {
    int on_line = 0;
    for (const auto& e : entries) on_line += line.find(e) != std::string::npos;
    EXPECT_LE(on_line, 1) << "legend entries run together:\n" << out;
  }
  for (const auto& e : entries) EXPECT_NE(out.find(e), std::string::npos) << out;
}

TEST(Plotter, UnknownPathListsWhatThereWas) {
  const std::string dir = temp_dir("plotter_bad");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess p({bin("plotter"), "joint_states.speed[0]", "--log", dir + "/run.lcmlog", "--output",
                  dir + "/plot.png"});
  EXPECT_EQ(p.wait(30.0), 1);
  const std::string out = p.output();
  EXPECT_NE(out.find("plotter: error: no data for joint_states.speed[0]"), std::string::npos) << out;
  EXPECT_NE(out.find("joint_states: joint_states.utime, joint_states.position[j1]"), std::string::npos) << out;
  EXPECT_NE(out.find("joint_states.velocity[j2]"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/plot.png"));
}

TEST(Plotter, DashboardLabelsTheTerminalWithoutAFileAndTheNearestFieldsForATypo) {
  const std::string dir = temp_dir("plotter_labels");
  write_test_log(dir + "/run.lcmlog");
  ChildProcess text({bin("plotter"), "joint_states.position[j2]", "/joint_states/velocity[j1]", "--log",
                     dir + "/run.lcmlog", "--terminal", "--data", dir + "/plot.dat"});
  ASSERT_EQ(text.wait(30.0), 0) << text.output();
  EXPECT_NE(text.output().find("joint_states.position[j2] [rad or m]"), std::string::npos) << text.output();
  const auto blocks = read_blocks(dir + "/plot.dat");
  ASSERT_EQ(blocks.size(), 2u);
  ASSERT_EQ(blocks[0].size(), 50u);
  EXPECT_DOUBLE_EQ(blocks[0][10].second, std::sin(1.0));  // position[1] of the 11th joint_states
  EXPECT_DOUBLE_EQ(blocks[1][10].second, 0.5);            // velocity[0]
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), {}), 2) << "no image without --output";

  ChildProcess typo({bin("plotter"), "joint_states.postion[j2]", "--log", dir + "/run.lcmlog", "--terminal"});
  EXPECT_EQ(typo.wait(30.0), 1) << typo.output();
  EXPECT_NE(typo.output().find("plotter: error: no data for joint_states.postion[j2] in " + dir +
                               "/run.lcmlog; what there was:\n  joint_states: nearest: joint_states.position[j2], "
                               "joint_states.position[j1], joint_states.position[0], joint_states.position[1], joint_states.position\n"),
            std::string::npos)
      << typo.output();
  EXPECT_EQ(typo.output().find("..."), std::string::npos) << typo.output();

  ChildProcess neither({bin("plotter"), "joint_states.position[j2]", "--log", dir + "/run.lcmlog"});
  EXPECT_EQ(neither.wait(30.0), 2) << neither.output();
  EXPECT_NE(neither.output().find("give an image file (-o run.png or .svg), or --terminal for a text plot"),
            std::string::npos)
      << neither.output();
}

TEST(Plotter, ATextColumnIsAnErrorThatSaysSo) {
  const std::string dir = temp_dir("plotter_text");
  write_status_log(dir + "/run.lcmlog");
  ChildProcess text({bin("plotter"), "arm_controller/status.error[0]", "arm_controller/status.message", "--log",
                     dir + "/run.lcmlog", "--output", dir + "/plot.png"});
  EXPECT_EQ(text.wait(30.0), 1);
  const std::string out = text.output();
  EXPECT_NE(out.find("plotter: error: arm_controller/status.message: column message of channel arm_controller/status "
                     "holds text, not numbers"),
            std::string::npos)
      << out;
  EXPECT_FALSE(std::filesystem::exists(dir + "/plot.png"));

  ChildProcess numbers({bin("plotter"), "arm_controller/status.error[0]", "--log", dir + "/run.lcmlog", "--output",
                        dir + "/plot.png", "--data", dir + "/plot.dat"});
  ASSERT_EQ(numbers.wait(30.0), 0) << numbers.output();
  const auto blocks = read_blocks(dir + "/plot.dat");
  ASSERT_EQ(blocks.size(), 1u);
  ASSERT_EQ(blocks[0].size(), 3u);
  EXPECT_EQ(blocks[0][2].second, 1.0);
}

TEST(Plotter, LiveFromTheBus) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("plotter_live");
  ChildProcess p({bin("plotter"), "joint_states.position[0]", "--duration", "1.0", "--output", dir + "/live.png",
                  "--data", dir + "/live.dat", "--lcm-url", url});
  ASSERT_TRUE(p.wait_for_output("listening", 5.0)) << p.output();
  lcm::LCM lc(url);
  joint_state_t js{};
  js.num_joints = 1;
  js.name = {"j1"};
  js.velocity = {0};
  js.effort = {0};
  for (int k = 0; k < 20; ++k) {
    js.utime = k;
    js.position = {double(k)};
    lc.publish("joint_states", &js);
    pump_until(lc, [] { return false; }, 0.01);
  }
  ASSERT_EQ(p.wait(10.0), 0) << p.output();
  const auto blocks = read_blocks(dir + "/live.dat");
  ASSERT_EQ(blocks.size(), 1u);
  ASSERT_EQ(blocks[0].size(), 20u);
  EXPECT_EQ(blocks[0][19].second, 19.0);
  EXPECT_GT(std::filesystem::file_size(dir + "/live.png"), 1000u);
}

TEST(Plotter, ATitleOrOutputNameCannotRunGnuplotCommands) {
  const std::string dir = temp_dir("plotter_injection");
  write_test_log(dir + "/run.lcmlog");
  const std::string marker = dir + "/ran";
  ChildProcess p({bin("plotter"), "/j2_controller/command", "--log", dir + "/run.lcmlog", "--output",
                  dir + "/plot.svg", "--title", "x\nsystem(\"touch " + marker + "\")\nset title \"y"});
  ASSERT_EQ(p.wait(30.0), 0) << p.output();
  EXPECT_FALSE(std::filesystem::exists(marker)) << "the title ran a command";
  EXPECT_NE(read_text(dir + "/plot.svg").find("<svg"), std::string::npos);
}
