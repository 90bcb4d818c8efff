// replay --sim (closed loop): the lockstep demo recorded with `bus record` re-runs bit for bit, simulation and
// controller manager, from the configurations the run recorded; a changed gain of the simulated PID diverges on
// joint_states; a log without sim_server's configuration is refused with exit 2, naming what to pass.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <fstream>
#include <regex>
#include <string>

#include "test/e2e/session.hpp"

namespace lcm_control::testing {
namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

std::string record_demo(const std::string& dir, double seconds) {
  RobotSession bus(source("config/turret_bot.urdf"), source("config/turret_bot.yaml"));
  const std::string log = dir + "/demo.lcmlog";
  auto recorder = bus.background({"bus", "record", log, "--force"});
  EXPECT_TRUE(recorder->wait_for_output("bus record: recording", 10)) << recorder->output();
  std::string out;
  EXPECT_EQ(bus.run({"launch", source("config/turret_bot_demo.launch.yaml"), "--duration", std::to_string(seconds)},
                    &out, 60),
            0)
      << out;
  EXPECT_EQ(recorder->stop(10), 0) << recorder->output();
  return log;
}

struct Replayed {
  int rc = -1;
  std::string out;
};

Replayed replay(const std::vector<std::string>& args) {
  RobotSession any(source("config/turret_bot.urdf"), source("config/turret_bot.yaml"));
  Replayed r;
  std::vector<std::string> argv = {"replay"};
  argv.insert(argv.end(), args.begin(), args.end());
  r.rc = any.run(argv, &r.out, 120);
  return r;
}

TEST(ReplaySim, TheLockstepDemoReRunsBitForBitAndAChangedGainDiverges) {
  const std::string dir = temp_dir("replay_sim");
  const std::string log = record_demo(dir, 3);
  const Replayed same = replay({log, "--sim"});
  std::printf("%s", same.out.c_str());
  EXPECT_EQ(same.rc, 0) << same.out;
  EXPECT_TRUE(has(same.out, "identical: ")) << same.out;
  EXPECT_TRUE(has(same.out, "note: closed loop: sim_server as recorded")) << same.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(same.out, m, std::regex(R"(hardware/command: (\d+) compared, 0 differ)"))) << same.out;
  EXPECT_GE(std::stoi(m[1]), 3000);
  ASSERT_TRUE(std::regex_search(same.out, m, std::regex(R"(joint_states: (\d+) compared, 0 differ)"))) << same.out;
  EXPECT_GE(std::stoi(m[1]), 170);

  // j2's simulated PID a little stiffer: the commands (expressions of time) stay, the robot moves otherwise.
  std::ifstream in(source("config/turret_bot.yaml"));
  std::string tuned((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string from = "    j2:\n      p: 1\n", to = "    j2:\n      p: 1.5\n";
  ASSERT_NE(tuned.find(from), std::string::npos);
  tuned.replace(tuned.find(from), from.size(), to);
  const std::string yaml = dir + "/tuned.yaml";
  std::ofstream(yaml) << tuned;
  const Replayed changed = replay({log, "--sim", "--config", yaml});
  std::printf("%s", changed.out.c_str());
  EXPECT_EQ(changed.rc, 1) << changed.out;
  // j2 rides on j1's slider: the first joint_states after j2 moves differ, j1's position first (by 3e-7 m).
  EXPECT_TRUE(std::regex_search(changed.out,
                                std::regex(R"(diverged: first on joint_states at t=0\.0\d+ s, position\[j[12]\])")))
      << changed.out;
  EXPECT_TRUE(has(changed.out, "hardware/command: ") && std::regex_search(changed.out, std::regex(
                                                             R"(hardware/command: \d+ compared, 0 differ)")))
      << changed.out;
}

TEST(ReplaySim, ALogWithoutSimServersConfigurationIsRefusedSayingWhy) {
  const std::string dir = temp_dir("replay_sim_bad");
  const std::string log = record_demo(dir, 1);
  const std::string cut = dir + "/no_sim_config.lcmlog";
  {
    lcm::LogFile in(log, "r"), out(cut, "w");
    ASSERT_TRUE(in.good() && out.good());
    for (const lcm::LogEvent* e = in.readNextEvent(); e; e = in.readNextEvent()) {
      if (e->channel == "sim_server/config") continue;
      lcm::LogEvent kept = *e;
      ASSERT_EQ(out.writeEvent(&kept), 0);
    }
  }
  const Replayed r = replay({cut, "--sim"});
  EXPECT_EQ(r.rc, 2) << r.out;
  EXPECT_TRUE(has(r.out, "sim_server/config")) << r.out;
  EXPECT_TRUE(has(r.out, "record with bus record")) << r.out;
}

}  // namespace
}  // namespace lcm_control::testing
