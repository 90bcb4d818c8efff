// lcm-spy decodes a real session: turret_bot brought up by `launch` (real time,
// as the tutorial runs it, with state-publisher), driven with turret-cmd, tuned,
// listed with cmctl and e-stopped, recorded on every channel by lcm-logger;
// DecodeLog (lcm-spy's own type lookup) finds a type for every event. Real time,
// not lockstep: recording every channel of a lockstep run overflows lcm-logger's
// queue (test/e2e/session.hpp), which can drop a channel's only messages.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>

#include "lcm_control/e_stop_t.hpp"
#include "test/e2e/session.hpp"

namespace fs = std::filesystem;
namespace lt = lcm_control::testing;

namespace {

void publish_e_stop(lcm::LCM& lc, bool engaged) {
  lcm_control::e_stop_t m{};
  m.engaged = engaged;
  m.source = "spy_session_test";
  lc.publish("e_stop", &m);
}

}  // namespace

TEST(LcmSpySession, EveryChannelOfARealSessionDecodes) {
  const fs::path share = fs::path(LCM_CONTROL_BIN_DIR).parent_path() / "share";
  if (!fs::exists(share / "decode_log.jar") || !fs::exists(share / "lcm_control_types.jar") ||
      !fs::exists("/usr/bin/java"))
    GTEST_SKIP() << "no JDK at build time";
  const std::string dir = lt::temp_dir("spy_session");
  const std::string log = dir + "/session.lcmlog";
  const std::string url = lt::unique_lcm_url();
  const std::map<std::string, std::string> env{{"LCM_DEFAULT_URL", url}};

  auto recorder = lt::start_lcm_logger(url, log);
  lt::ChildProcess launch({lt::bin("launch"), lt::source("config/turret_bot.launch.yaml"), "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("started joint_state_controller, j1_controller, j2_controller", 40))
      << launch.output();

  lt::ChildProcess j1({lt::bin("turret-cmd"), "j1_controller", "0.5"}, env);
  EXPECT_EQ(j1.wait(15), 0) << j1.output();
  lt::ChildProcess j2({lt::bin("turret-cmd"), "j2_controller", "3.14*sin(i/100)", "--rate", "60", "--sim-time",
                       "--count", "120"},
                      env);
  EXPECT_EQ(j2.wait(30), 0) << j2.output();
  lt::ChildProcess tune({lt::bin("tune"), "j2", "--p", "2"}, env);
  EXPECT_EQ(tune.wait(15), 0) << tune.output();
  lt::ChildProcess list({lt::bin("cmctl"), "list"}, env);
  EXPECT_EQ(list.wait(15), 0) << list.output();
  {
    lcm::LCM lc(url);
    ASSERT_TRUE(lc.good());
    publish_e_stop(lc, true);
    publish_e_stop(lc, false);
  }
  // Two more seconds of wall time (statistics come once a wall-clock second), then
  // everything stops (the spawner unloads: more requests).
  lt::ChildProcess more({lt::bin("turret-cmd"), "j2_controller", "0", "--rate", "60", "--duration", "2"}, env);
  EXPECT_EQ(more.wait(30), 0) << more.output();
  EXPECT_EQ(launch.stop(20), 0) << launch.output();
  EXPECT_EQ(recorder->stop(10), 0) << recorder->output();

  // liblcm's udpm provider publishes a few LCM_SELF_TEST packets (raw bytes, no
  // type) when a process first listens; lcm-spy lists them as undecodable too.
  // They are LCM's own, not ours: the raw log must show no other undecodable
  // channel, and the log without them must decode completely.
  const std::string classpath = "/usr/share/java/lcm.jar:" + (share / "lcm_control_types.jar").string() + ":" +
                                (share / "decode_log.jar").string();
  {
    lt::ChildProcess raw({"/usr/bin/java", "-cp", classpath, "DecodeLog", log});
    raw.wait(50);
    std::istringstream lines(raw.output());
    for (std::string l; std::getline(lines, l);)
      if (l.find("UNDECODABLE") != std::string::npos) {
        EXPECT_EQ(l.rfind("LCM_SELF_TEST UNDECODABLE", 0), 0u) << l;
      }
  }
  const std::string ours = dir + "/session_ours.lcmlog";
  int copied = 0;
  {
    lcm::LogFile in(log, "r"), out(ours, "w");
    ASSERT_TRUE(in.good() && out.good());
    for (const lcm::LogEvent* ev = in.readNextEvent(); ev; ev = in.readNextEvent())
      if (ev->channel != "LCM_SELF_TEST") {
        lcm::LogEvent copy = *ev;
        ASSERT_EQ(out.writeEvent(&copy), 0);
        ++copied;
      }
  }
  lt::ChildProcess decode({"/usr/bin/java", "-cp", classpath, "DecodeLog", ours});
  ASSERT_EQ(decode.wait(50), 0) << decode.output();
  const std::string out = "\n" + decode.output();
  EXPECT_NE(out.find("events " + std::to_string(copied) + ", undecodable 0"), std::string::npos) << out;
  std::printf("%s", out.c_str());
  EXPECT_EQ(out.find("UNDECODABLE"), std::string::npos) << out;
  for (const char* line :
       {"hardware/state lcm_control.hardware_state_t", "hardware/command lcm_control.hardware_command_t",
        "joint_states lcm_control.joint_state_t", "j1_controller/command lcm_control.float64_t",
        "j2_controller/command lcm_control.float64_t", "controller_manager/request lcm_control.cm_request_t",
        "controller_manager/response lcm_control.cm_response_t", "sim_server/statistics lcm_control.loop_stats_t",
        "controller_manager/statistics lcm_control.loop_stats_t", "clock lcm_control.sim_clock_t",
        "sim_server/gains/set lcm_control.pid_gains_t", "sim_server/gains lcm_control.pid_gains_t",
        "link_poses lcm_control.link_poses_t", "e_stop lcm_control.e_stop_t 2"})
    EXPECT_NE(out.find(std::string("\n") + line), std::string::npos) << "missing: " << line << "\n" << out;
}
