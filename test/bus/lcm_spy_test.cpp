// lcm-spy can decode every message type: a log holding one message of each
// type goes through DecodeLog, which looks types up exactly as lcm-spy does.
#include <gtest/gtest.h>
#include <lcm/lcm-cpp.hpp>

#include <filesystem>

#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/controller_info_t.hpp"
#include "lcm_control/controller_state_t.hpp"
#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/hardware_state_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "lcm_control/loop_stats_t.hpp"
#include "lcm_control/pid_gains_t.hpp"
#include "lcm_control/sim_clock_t.hpp"
#include "lcm_control/trajectory_point_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "test/support/process.hpp"

namespace fs = std::filesystem;
namespace lt = lcm_control::testing;

namespace {

template <class Msg>
void write_event(lcm::LogFile& log, int64_t t, const std::string& channel) {
  Msg m{};
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  lcm::LogEvent ev{};
  ev.eventnum = t;
  ev.timestamp = t;
  ev.channel = channel;
  ev.datalen = static_cast<int32_t>(buf.size());
  ev.data = buf.data();
  ASSERT_EQ(log.writeEvent(&ev), 0);
}

struct Jars {
  std::string classpath;
  bool ok = false;
};

Jars jars() {
  const fs::path share = fs::path(LCM_CONTROL_BIN_DIR).parent_path() / "share";
  Jars j;
  j.classpath = "/usr/share/java/lcm.jar:" + (share / "lcm_control_types.jar").string() + ":" +
                (share / "decode_log.jar").string();
  j.ok = fs::exists(share / "decode_log.jar") && fs::exists(share / "lcm_control_types.jar") &&
         fs::exists("/usr/bin/java");
  return j;
}

}  // namespace

TEST(LcmSpy, DecodesEveryMessageType) {
  const Jars j = jars();
  if (!j.ok) GTEST_SKIP() << "no JDK at build time";
  const std::string path = lt::temp_dir("spy") + "/all.lcmlog";
  {
    lcm::LogFile log(path, "w");
    ASSERT_TRUE(log.good());
    int64_t t = 1;
    write_event<lcm_control::cm_request_t>(log, t++, "controller_manager/request");
    write_event<lcm_control::cm_response_t>(log, t++, "controller_manager/response");
    write_event<lcm_control::controller_info_t>(log, t++, "info");
    write_event<lcm_control::controller_state_t>(log, t++, "j2_controller/state");
    write_event<lcm_control::e_stop_t>(log, t++, "e_stop");
    write_event<lcm_control::float64_array_t>(log, t++, "group/command");
    write_event<lcm_control::float64_t>(log, t++, "j2_controller/command");
    write_event<lcm_control::hardware_command_t>(log, t++, "hardware/command");
    write_event<lcm_control::hardware_state_t>(log, t++, "hardware/state");
    write_event<lcm_control::joint_state_t>(log, t++, "joint_states");
    write_event<lcm_control::joint_trajectory_t>(log, t++, "traj/command");
    write_event<lcm_control::link_poses_t>(log, t++, "link_poses");
    write_event<lcm_control::loop_stats_t>(log, t++, "sim_server/statistics");
    write_event<lcm_control::pid_gains_t>(log, t++, "sim_server/gains");
    write_event<lcm_control::sim_clock_t>(log, t++, "clock");
    write_event<lcm_control::trajectory_point_t>(log, t++, "point");
    write_event<lcm_control::trajectory_status_t>(log, t++, "traj/result");
  }
  lt::ChildProcess p({"/usr/bin/java", "-cp", j.classpath, "DecodeLog", path});
  ASSERT_EQ(p.wait(60), 0) << p.output();
  const std::string out = p.output();
  EXPECT_NE(out.find("events 17, undecodable 0"), std::string::npos) << out;
  EXPECT_NE(out.find("joint_states lcm_control.joint_state_t 1"), std::string::npos) << out;
  EXPECT_NE(out.find("hardware/state lcm_control.hardware_state_t 1"), std::string::npos) << out;
}

TEST(LcmSpy, ReportsAnUndecodableMessage) {
  const Jars j = jars();
  if (!j.ok) GTEST_SKIP() << "no JDK at build time";
  const std::string path = lt::temp_dir("spy") + "/bad.lcmlog";
  {
    lcm::LogFile log(path, "w");
    uint8_t junk[16] = {1, 2, 3, 4, 5, 6, 7, 8, 9};
    lcm::LogEvent ev{};
    ev.channel = "mystery";
    ev.datalen = sizeof(junk);
    ev.data = junk;
    ASSERT_EQ(log.writeEvent(&ev), 0);
  }
  lt::ChildProcess p({"/usr/bin/java", "-cp", j.classpath, "DecodeLog", path});
  EXPECT_EQ(p.wait(60), 1) << p.output();
  EXPECT_NE(p.output().find("mystery UNDECODABLE"), std::string::npos) << p.output();
}
