// lcm-logger / lcm-logplayer: a turret_bot session in real time (j1 to 0.5, j2
// driven with the tutorial's 3.14*sin(i/100) at 60 Hz of sim time) is recorded
// by the real lcm-logger while state-logger writes joint_states live; the log
// holds every row, and replayed by lcm-logplayer onto a second bus gives a
// fresh state-logger exactly the live CSV, and the plotter (live on the replay
// bus, and --log on the file) the same points.
//
// Real time and a paced replay, because both LCM tools lose datagrams past
// rates no user records at: lcm-logger keeps 30 unhandled messages per
// subscription (15 ms of a lockstep session's 2,000 a second on these
// channels), and `lcm-logplayer -s 0` sends the whole log in a few ms into a
// receive buffer of 212,992 bytes where rmem_max cannot be raised (CI's
// container): a loaded CI run lost 2 of 361 rows in either of those ways.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test/e2e/session.hpp"

namespace lt = lcm_control::testing;

namespace {

struct Table {
  std::string header;
  std::vector<std::string> rows;  // sorted by utime (first column), as written
};

Table read_table(const std::string& path) {
  Table t;
  std::istringstream in(lt::file_text(path));
  std::getline(in, t.header);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) t.rows.push_back(line);
  std::stable_sort(t.rows.begin(), t.rows.end(), [](const std::string& a, const std::string& b) {
    return std::stoll(a.substr(0, a.find(','))) < std::stoll(b.substr(0, b.find(',')));
  });
  return t;
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string c; std::getline(ss, c, ',');) out.push_back(c);
  return out;
}

// The plotter's --data file: per path "# path (...)" then "t value" lines.
std::vector<std::vector<std::pair<double, double>>> read_plot_data(const std::string& path) {
  std::vector<std::vector<std::pair<double, double>>> blocks;
  std::istringstream in(lt::file_text(path));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("# ", 0) == 0) {
      blocks.emplace_back();
      continue;
    }
    if (line.empty() || blocks.empty()) continue;
    double t = 0, v = 0;
    if (std::sscanf(line.c_str(), "%lf %lf", &t, &v) == 2) blocks.back().emplace_back(t, v);
  }
  return blocks;
}

// The plotter's points (x = utime from the first message) equal the CSV's columns.
void expect_plot_matches(const std::string& data_file, const Table& csv, const std::vector<int>& columns,
                         const std::string& what) {
  const auto blocks = read_plot_data(data_file);
  ASSERT_EQ(blocks.size(), columns.size()) << what << "\n" << lt::file_text(data_file).substr(0, 2000);
  const long long u0 = std::stoll(cells(csv.rows.front())[0]);
  for (size_t b = 0; b < blocks.size(); ++b) {
    auto points = blocks[b];
    std::stable_sort(points.begin(), points.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    ASSERT_EQ(points.size(), csv.rows.size()) << what << " path " << b;
    for (size_t k = 0; k < points.size(); ++k) {
      const auto c = cells(csv.rows[k]);
      EXPECT_NEAR(points[k].first, double(std::stoll(c[0]) - u0) * 1e-6, 1e-6) << what << " row " << k;
      EXPECT_EQ(points[k].second, std::stod(c[size_t(columns[b])])) << what << " path " << b << " row " << k;
    }
  }
}

}  // namespace

TEST(Replay, LogplayerReproducesTheLiveCsvAndPlot) {
  const std::string dir = lt::temp_dir("replay");
  const std::string log = dir + "/turret_run.lcmlog";
  const std::string live_csv = dir + "/live.csv", replay_csv = dir + "/replay.csv";

  // 1. The live session, recorded.
  lt::TurretBot bot(lt::unique_lcm_url());
  bot.bring_up_controllers();
  if (HasFatalFailure()) return;
  auto recorder = lt::start_lcm_logger(bot.url(), log, "joint_states|j1_controller/command|j2_controller/command");
  lt::ChildProcess live_logger({lt::bin("state-logger"), "joint_states", "--output", live_csv}, bot.env());
  ASSERT_TRUE(live_logger.wait_for_output("state-logger: logging", 15)) << live_logger.output();
  lt::ChildProcess j1({lt::bin("turret-cmd"), "j1_controller", "0.5"}, bot.env());
  ASSERT_EQ(j1.wait(15), 0) << j1.output();
  lt::ChildProcess j2({lt::bin("turret-cmd"), "j2_controller", "3.14*sin(i/100)", "--rate", "60", "--sim-time",
                       "--timeout", "30"},
                      bot.env());
  bot.run_sim(6.0, "realtime");
  if (HasFatalFailure()) return;
  // Nothing publishes joint_states once sim_server has stopped; let the last ones arrive.
  EXPECT_TRUE(j2.running()) << j2.output();
  lt::ChildProcess quiet({"/bin/sleep", "0.5"});
  quiet.wait(5);
  EXPECT_EQ(live_logger.stop(10), 0) << live_logger.output();
  EXPECT_EQ(recorder->stop(10), 0) << recorder->output();
  j2.stop(5);
  bot.shut_down();

  const Table live = read_table(live_csv);
  ASSERT_EQ(live.header, "utime,position[0],position[1],velocity[0],velocity[1],effort[0],effort[1],name[0],name[1]");
  // joint_state_controller publishes at 60 Hz of sim time (turret_bot.yaml) while the controllers run.
  ASSERT_GE(live.rows.size(), 300u) << live_logger.output();
  ASSERT_LE(live.rows.size(), 361u);
  // j2 follows the sine: it moved well away from 0.
  double max_j2 = 0;
  for (const auto& r : live.rows) max_j2 = std::max(max_j2, std::abs(std::stod(cells(r)[2])));
  EXPECT_GT(max_j2, 1.0);

  // 2. The log has every row the live logger wrote.
  ASSERT_EQ(lt::ChildProcess({lt::bin("log2csv"), log, "--output-dir", dir + "/log_csv", "--channel", "^joint_states$"})
                .wait(30),
            0);
  const Table logged = read_table(dir + "/log_csv/joint_states.csv");
  ASSERT_EQ(logged.rows.size(), live.rows.size()) << "lcm-logger lost messages: " << recorder->output();
  for (size_t k = 0; k < live.rows.size(); ++k) ASSERT_EQ(logged.rows[k], live.rows[k]) << "log2csv row " << k;

  // 3. The log replayed at 4x its recorded pace onto a bus of its own.
  const std::string replay_url = lt::unique_lcm_url();
  const std::map<std::string, std::string> replay_env{{"LCM_DEFAULT_URL", replay_url}};
  lt::ChildProcess replay_logger({lt::bin("state-logger"), "--output", replay_csv}, replay_env);
  ASSERT_TRUE(replay_logger.wait_for_output("state-logger: logging", 15)) << replay_logger.output();
  lt::ChildProcess live_plot({lt::bin("plotter"), "joint_states.position[1]", "joint_states.velocity[1]", "--duration",
                              "4", "--time", "utime", "--data", dir + "/live_plot.dat", "--output",
                              dir + "/live_plot.svg"},
                             replay_env);
  ASSERT_TRUE(live_plot.wait_for_output("plotter: listening", 15)) << live_plot.output();
  // Only joint_states, which both readers take.
  lt::ChildProcess player({"/usr/bin/lcm-logplayer", "-s", "4", "-e", "^joint_states$", "-l", replay_url, log});
  ASSERT_EQ(player.wait(30), 0) << player.output();
  lt::ChildProcess settle({"/bin/sleep", "0.5"});
  settle.wait(5);
  EXPECT_EQ(replay_logger.stop(10), 0) << replay_logger.output();

  const Table replayed = read_table(replay_csv);
  EXPECT_EQ(replayed.header, live.header);
  ASSERT_EQ(replayed.rows.size(), live.rows.size()) << "the replay lost messages: " << replay_logger.output();
  for (size_t k = 0; k < live.rows.size(); ++k) ASSERT_EQ(replayed.rows[k], live.rows[k]) << "row " << k;
  std::printf("replay: %zu joint_states rows identical (live, lcm-logger's log, lcm-logplayer -s 4)\n",
              live.rows.size());

  // 4. The plotter: live on the replay bus, and from the file.
  ASSERT_EQ(live_plot.wait(30), 0) << live_plot.output();
  expect_plot_matches(dir + "/live_plot.dat", live, {2, 4}, "plotter (live replay)");
  lt::ChildProcess file_plot({lt::bin("plotter"), "j2_controller/command.data", "joint_states.position[1]",
                              "joint_states.velocity[1]", "--log", log, "--time", "utime", "--data",
                              dir + "/log_plot.dat", "--output", dir + "/log_plot.png"});
  ASSERT_EQ(file_plot.wait(30), 0) << file_plot.output();
  auto blocks = read_plot_data(dir + "/log_plot.dat");
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_GE(blocks[0].size(), 300u);  // the commands j2 got, 60 Hz of sim time
  const std::string file_data = lt::file_text(dir + "/log_plot.dat");
  // Same points as the live CSV for the joint_states paths (drop the command block).
  {
    std::ofstream out(dir + "/log_plot_js.dat");
    out << file_data.substr(file_data.find("\n\n\n") + 3);
  }
  // t0 of the file plot is the first command's utime, not the first joint_states'; compare values only.
  const auto js = read_plot_data(dir + "/log_plot_js.dat");
  ASSERT_EQ(js.size(), 2u);
  for (size_t b = 0; b < 2; ++b) {
    ASSERT_EQ(js[b].size(), live.rows.size());
    auto pts = js[b];
    std::stable_sort(pts.begin(), pts.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for (size_t k = 0; k < pts.size(); ++k)
      EXPECT_EQ(pts[k].second, std::stod(cells(live.rows[k])[b == 0 ? 2 : 4])) << "plotter --log path " << b;
  }
}
