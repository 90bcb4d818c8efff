// scripts/demo, 5 s of sim time instead of 20: two fast (lockstep) runs print
// the same tracking figures and record the same joint_states CSV, a real-time
// run's RMS agrees within 5%, a run with the hardware loop over shared memory
// tracks bit for bit as over LCM, and the PNG and its data match the CSV.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "test/support/process.hpp"

using namespace lcm_control::testing;
namespace fs = std::filesystem;

namespace {

std::string read(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Runs the demo into a fresh folder; returns the folder.
fs::path run_demo(const std::string& name, bool realtime, const std::vector<std::string>& extra = {}) {
  const fs::path dir = fs::temp_directory_path() / ("lcm_control_demo_test_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  std::vector<std::string> argv{"/bin/bash", source("scripts/demo"), "--no-build", "--duration", "5", "--output-dir",
                                dir.string()};
  if (realtime) argv.push_back("--realtime");
  argv.insert(argv.end(), extra.begin(), extra.end());
  ChildProcess demo(argv, {{"BIN_DIR", LCM_CONTROL_BIN_DIR}});
  EXPECT_EQ(demo.wait(40.0), 0) << demo.output();
  EXPECT_NE(demo.output().find("tracking over"), std::string::npos) << demo.output();
  return dir;
}

// The summary without the timing line (wall time varies by machine).
std::string tracking_part(const fs::path& dir) {
  std::stringstream in(read(dir / "summary.txt")), out;
  for (std::string line; std::getline(in, line);)
    if (line.rfind("timing", 0) != 0) out << line << "\n";
  return out.str();
}

double j2_rms(const fs::path& dir) {
  std::smatch m;
  const std::string s = read(dir / "summary.txt");
  if (!std::regex_search(s, m, std::regex(R"(j2: rms error ([0-9.]+))"))) return -1;
  return std::stod(m[1]);
}

}  // namespace

TEST(Demo, FastRunsRepeatExactlyAndRealTimeAgrees) {
  const fs::path a = run_demo("fast_a", false), b = run_demo("fast_b", false);
  const std::string ta = tracking_part(a);
  ASSERT_NE(ta.find("j2: rms error"), std::string::npos) << ta;
  EXPECT_EQ(ta, tracking_part(b));
  EXPECT_NE(ta.find("301 joint_states messages"), std::string::npos) << ta;
  const std::string csv = read(a / "csv/joint_states.csv");
  EXPECT_GT(csv.size(), 1000u);
  EXPECT_EQ(csv, read(b / "csv/joint_states.csv"));
  EXPECT_EQ(read(a / "csv/j2_controller__command.csv"), read(b / "csv/j2_controller__command.csv"));

  const fs::path r = run_demo("realtime", true);
  const double fast = j2_rms(a), real = j2_rms(r);
  std::printf("j2 rms error over 5 s: fast %.6f, real time %.6f\n", fast, real);
  ASSERT_GT(fast, 0);
  EXPECT_NEAR(real, fast, 0.05 * fast) << read(r / "summary.txt");
  for (const auto& d : {a, b, r}) fs::remove_all(d);
}

// The tutorial with the hardware loop over shared memory (--hardware-url shm:NAME): the tracking bounds hold and
// joint_states and the commands are the same, bit for bit, as over LCM; the segment is gone afterwards.
TEST(Demo, OverSharedMemoryTheTutorialTracksBitForBitAsOverLcm) {
  const std::string segment = "demo-test-" + std::to_string(getpid());
  const fs::path lcm = run_demo("over_lcm", false), shm = run_demo("over_shm", false, {"--hardware-url", "shm:" + segment});
  EXPECT_NE(read(shm / "launch.out").find("hardware loop on shm:" + segment), std::string::npos) << read(shm / "launch.out");
  const std::string t = tracking_part(shm);
  EXPECT_NE(t.find("301 joint_states messages"), std::string::npos) << t;
  EXPECT_EQ(t, tracking_part(lcm));
  const double rms = j2_rms(shm);
  std::printf("over shared memory: j2 rms error over 5 s %.6f\n", rms);
  EXPECT_GT(rms, 0.0);
  EXPECT_LT(rms, 0.25) << "j2 follows 3.14*sin(i/100) with the tutorial's gains";
  EXPECT_EQ(read(shm / "csv/joint_states.csv"), read(lcm / "csv/joint_states.csv"));
  EXPECT_EQ(read(shm / "csv/j2_controller__command.csv"), read(lcm / "csv/j2_controller__command.csv"));
  EXPECT_FALSE(fs::exists("/dev/shm/lcm_control." + segment));
  for (const auto& d : {lcm, shm}) fs::remove_all(d);
}

// The PNG is there and the plotted points are the CSV's rows (t in sim seconds).
TEST(Demo, PlotShowsTheCsvData) {
  const fs::path dir = run_demo("plot", false);
  ASSERT_TRUE(fs::exists(dir / "demo-j2.png"));
  EXPECT_GT(fs::file_size(dir / "demo-j2.png"), 1000u);
  const std::string png = read(dir / "demo-j2.png");
  EXPECT_EQ(png.substr(1, 3), "PNG");
  // Data blocks in order: command, position[1], velocity[1].
  std::vector<std::vector<std::pair<double, double>>> blocks;
  std::stringstream in(read(dir / "demo-j2-plot.dat"));
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#", 0) == 0) {
      blocks.emplace_back();
    } else if (!line.empty() && !blocks.empty()) {
      std::stringstream l(line);
      double t = 0, v = 0;
      l >> t >> v;
      blocks.back().emplace_back(t, v);
    }
  }
  ASSERT_EQ(blocks.size(), 3u);
  std::stringstream csv(read(dir / "csv/joint_states.csv"));
  std::string line;
  std::getline(csv, line);
  ASSERT_EQ(line, "utime,position[0],position[1],velocity[0],velocity[1],effort[0],effort[1],name[0],name[1]");
  size_t row = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> v;
    std::stringstream l(line);
    for (std::string cell; std::getline(l, cell, ',');) v.push_back(cell);
    ASSERT_EQ(v.size(), 9u) << line;
    EXPECT_EQ(v[8], "j2") << row;
    ASSERT_LT(row, blocks[1].size());
    EXPECT_NEAR(blocks[1][row].first, std::stod(v[0]) * 1e-6, 1e-6) << row;  // the first message is at sim time 0
    EXPECT_NEAR(blocks[1][row].second, std::stod(v[2]), 1e-12) << row;
    EXPECT_NEAR(blocks[2][row].second, std::stod(v[4]), 1e-12) << row;
    ++row;
  }
  EXPECT_EQ(row, blocks[1].size());
  EXPECT_EQ(blocks[0].size(), 301u);
  fs::remove_all(dir);
}
