// Limits, end to end (issue 35): turret_bot with its trajectory controller in real time, while this test sends
// what a careless or hostile peer might: first fragments of huge messages and messages that never complete
// (item 4), trajectory goals too large to take (item 5), robots of thousands of links (item 6), and goals meant to
// flood or forge the log (item 1). Each test prints its figures as a RELIABILITY line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include <fmt/format.h>

#include "bus/lcm_socket.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/trajectory_status_t.hpp"
#include "test/e2e/session.hpp"
#include "test/reliability/limits/goals.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;

namespace {

void sleep_s(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

// turret_bot with joint_state_controller and trajectory_controller, sim_server in real time.
struct Robot : lt::RobotSession {
  Robot() : RobotSession(lt::source("config/turret_bot.urdf"), lt::source("config/turret_bot_trajectory.yaml")) {}
  // hardware_url: the loop's --hardware-lcm-url ("": the shared bus).
  void bring_up(const std::string& hardware_url = "") {
    const std::vector<std::string> hw =
        hardware_url.empty() ? std::vector<std::string>{} : std::vector<std::string>{"--hardware-lcm-url", hardware_url};
    start_controller_manager(hw);
    ASSERT_NO_FATAL_FAILURE(spawn({"joint_state_controller", "trajectory_controller"}));
    ASSERT_NO_FATAL_FAILURE(start_sim(hw, 20));
  }
  pid_t sim_pid() const { return sim_ ? sim_->pid() : -1; }
};

// Fragment `number` of `count` of message `seqno` (`total` bytes) at `offset`, `bytes` long; fragment 0 carries the
// channel.
void send_fragment(lt::RawSender& sender, uint32_t seqno, uint32_t total, uint32_t offset, uint16_t number,
                   uint16_t count, const std::string& channel, size_t bytes) {
  sender.send(lt::lcm_fragment(seqno, total, offset, number, count,
                               number == 0 ? lt::named_payload(channel, bytes) : std::vector<uint8_t>(bytes, 0x5a)));
}

using lt::goal_of;

}  // namespace

// Item 4: eight senders on a channel the controller manager reads and eight on one the simulator reads each send the
// first fragment of a 16 MB message and then 3 MB of a 3.5 MB message that never completes. Neither program keeps
// that memory (before, each kept 4 x 16 MB for good: a first fragment sized the buffer for the whole message).
TEST(Limits, FragmentsOfHugeOrUnfinishedMessagesAreNotHeld) {
  Robot robot;
  ASSERT_NO_FATAL_FAILURE(robot.bring_up());
  sleep_s(1.0);
  const long cm0 = lt::rss_kb(robot.controller_manager_pid()), sim0 = lt::rss_kb(robot.sim_pid());
  const size_t chunk = 60000;
  std::vector<std::unique_ptr<lt::RawSender>> senders;
  for (int s = 0; s < 16; ++s) senders.push_back(std::make_unique<lt::RawSender>(robot.url()));
  for (int s = 0; s < 16; ++s) {  // 8 senders on the controller manager's channel, 8 on the simulator's
    const std::string channel = s < 8 ? "trajectory_controller/command" : "hardware/command";
    send_fragment(*senders[size_t(s)], uint32_t(10 * s), 16u << 20, 0, 0, 300, channel, chunk);
    const uint32_t total = 3500000, count = total / chunk + 1;
    for (uint32_t k = 0; k < 50; ++k) {  // 3 MB of it, then silence
      send_fragment(*senders[size_t(s)], uint32_t(10 * s + 1), total, uint32_t(k * chunk), uint16_t(k),
                    uint16_t(count), channel, chunk);
      if (k % 4 == 3) sleep_s(0.002);  // at the pace the receivers read
    }
  }
  sleep_s(0.3);
  const long cm_peak = lt::rss_kb(robot.controller_manager_pid()), sim_peak = lt::rss_kb(robot.sim_pid());
  sleep_s(LcmSocket::kFragmentTimeoutUs * 1e-6 + 1.5);
  // A datagram after the timeout: the loops drop what they held when they next read their sockets.
  send_fragment(*senders[0], 99, 100, 0, 0, 1, "unrelated", 90);
  sleep_s(0.5);
  const long cm1 = lt::rss_kb(robot.controller_manager_pid()), sim1 = lt::rss_kb(robot.sim_pid());
  std::printf("RELIABILITY|limits|16 senders: a 16 MB first fragment + 3 MB of an unfinished 3.5 MB message each, on "
              "the manager's and the simulator's channels|tried=32|ok=%d|crashes=0|hangs=0|RSS controller_manager %ld -> peak %ld -> %ld kB, sim_server "
              "%ld -> peak %ld -> %ld kB (after the %.0f s fragment timeout)\n",
              (cm1 - cm0 < 5000 && sim1 - sim0 < 5000) ? 32 : 0, cm0, cm_peak, cm1, sim0, sim_peak, sim1,
              LcmSocket::kFragmentTimeoutUs * 1e-6);
  EXPECT_LT(cm1 - cm0, 5000) << "controller_manager kept fragments";
  EXPECT_LT(sim1 - sim0, 5000) << "sim_server kept fragments";
  EXPECT_LT(cm_peak - cm0, 40000) << "controller_manager held more than the data that arrived";
}

// Item 5: goals of 200,000 and 1,000,000 points (7 and 36 MB; 100,000 points, 3.6 MB, is under the limit). Each is refused on the trajectory's result channel, under its goal
// id, with the reason, and the controller manager writes one line for it.
TEST(Limits, AGoalTooLargeToTakeIsRefusedOnTheResultChannelWithOneLogLine) {
  Robot robot;
  ASSERT_NO_FATAL_FAILURE(robot.bring_up());
  lcm::LCM lc(robot.url());
  lt::Recorder<trajectory_status_t> results(lc, "trajectory_controller/result");
  std::string figures;
  for (const int points : {200000, 1000000}) {
    SCOPED_TRACE(points);
    const int64_t id = 7000 + points / 1000;
    const joint_trajectory_t g = goal_of(id, points);
    const int bytes = g.getEncodedSize();
    ASSERT_EQ(lc.publish("trajectory_controller/command", &g), 0);
    ASSERT_TRUE(lt::pump_until(lc, [&] {
      for (const auto& r : results.messages)
        if (r.goal_id == id) return true;
      return false;
    }, 10)) << robot.cm_output();
    const trajectory_status_t* r = nullptr;
    for (const auto& m : results.messages)
      if (m.goal_id == id) r = &m;
    EXPECT_EQ(r->status, trajectory_status_t::REJECTED) << r->message;
    EXPECT_NE(r->message.find(fmt::format("a message of {} bytes on 'trajectory_controller/command'", bytes)),
              std::string::npos)
        << r->message;
    sleep_s(0.3);
    const std::string out = robot.cm_output();
    size_t lines = 0;
    for (size_t at = out.find(fmt::format("a message of {} bytes", bytes)); at != std::string::npos;
         at = out.find(fmt::format("a message of {} bytes", bytes), at + 1))
      ++lines;
    EXPECT_EQ(lines, 1u) << out;
    figures += fmt::format("{} points ({} bytes): {}; ", points, bytes, r->message.substr(r->message.find("rejected")));
  }
  std::printf("RELIABILITY|limits|trajectory goals of 200,000 and 1,000,000 points (over 4 MiB)|tried=2|ok=%d|crashes=0|hangs=0|"
              "%s\n",
              ::testing::Test::HasFailure() ? 0 : 2, figures.c_str());
}

namespace {

// A serial chain of n revolute links with limits and effort transmissions, and a joint_state_controller: its files.
std::pair<std::string, std::string> write_chain(const std::string& folder, int n, bool fixed = false) {
  std::string urdf = "<robot name=\"chain\"><link name=\"base\"><inertial><mass value=\"1\"/><inertia ixx=\"0.01\" "
                     "iyy=\"0.01\" izz=\"0.01\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial></link>";
  for (int i = 0; i < n; ++i)
    urdf += fmt::format(
        "<link name=\"l{0}\"><inertial><origin xyz=\"0 0 0.05\"/><mass value=\"0.1\"/><inertia ixx=\"0.001\" "
        "iyy=\"0.001\" izz=\"0.001\" ixy=\"0\" ixz=\"0\" iyz=\"0\"/></inertial><collision><origin xyz=\"0 0 0.05\"/>"
        "<geometry><box size=\"0.02 0.02 0.1\"/></geometry></collision></link><joint name=\"j{0}\" type=\"{2}\">"
        "<parent link=\"{1}\"/><child link=\"l{0}\"/><origin xyz=\"0 0 0.1\"/><axis xyz=\"0 1 0\"/><limit lower=\"-1\" "
        "upper=\"1\" effort=\"10\" velocity=\"2\"/></joint>{3}",
        i, i == 0 ? std::string("base") : fmt::format("l{}", i - 1), fixed && i > 0 ? "fixed" : "revolute",
        fixed && i > 0 ? std::string()
                       : fmt::format("<transmission name=\"t{0}\"><type>transmission_interface/SimpleTransmission</type>"
                                     "<joint name=\"j{0}\"><hardwareInterface>hardware_interface/EffortJointInterface"
                                     "</hardwareInterface></joint><actuator name=\"m{0}\"><mechanicalReduction>1"
                                     "</mechanicalReduction></actuator></transmission>",
                                     i));
  urdf += "<gazebo><plugin name=\"gazebo_ros_control\" filename=\"libgazebo_ros_control.so\"/></gazebo></robot>";
  const std::string u = folder + fmt::format("/chain{}.urdf", n), y = folder + fmt::format("/chain{}.yaml", n);
  std::ofstream(u) << urdf;
  std::ofstream(y) << "joint_state_controller:\n  type: joint_state_controller/JointStateController\n  publish_rate: 50\n";
  return {u, y};
}

// sim_server started on the files for 0.01 s (how long it took), then doctor on them: exit codes and outputs.
struct Started {
  int sim_rc = 0, doctor_rc = 0;
  double sim_s = 0;
  std::string sim_out, doctor_out;
};
Started start_sim_and_doctor(const std::string& urdf, const std::string& config) {
  Started r;
  const auto t0 = std::chrono::steady_clock::now();
  lt::ChildProcess sim({lt::bin("sim_server"), "--urdf", urdf, "--config", config, "--duration", "0.01"},
                       {{"LCM_DEFAULT_URL", lt::unique_lcm_url()}});
  r.sim_rc = sim.wait(60);
  r.sim_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.sim_out = sim.output();
  lt::ChildProcess doctor({lt::bin("doctor"), "--urdf", urdf, "--config", config});
  r.doctor_rc = doctor.wait(60);
  r.doctor_out = doctor.output();
  return r;
}

}  // namespace

// Item 6: a 500-link chain is ready well within 10 s (27 s before: Bullet grew its Jacobian buffers one row at a
// time); 5,000 links are refused at once by doctor and sim_server, naming the limit.
TEST(Limits, ALongChainIsReadyQuicklyOrRefusedAtOnceWithTheLimitNamed) {
  const std::string folder = lt::temp_dir("limits_chain");
  std::string figures;
  for (const int n : {500, 5000}) {
    SCOPED_TRACE(n);
    const auto [urdf, config] = write_chain(folder, n);
    const Started r = start_sim_and_doctor(urdf, config);
    const int rc = r.sim_rc;
    const double s = r.sim_s;
    EXPECT_LT(s, 10.0) << r.sim_out;
    if (n <= 1000) {
      EXPECT_EQ(rc, 0) << r.sim_out;
      EXPECT_EQ(r.doctor_rc, 0) << r.doctor_out;
    } else {
      EXPECT_EQ(rc, 3) << r.sim_out;
      EXPECT_EQ(r.doctor_rc, 3) << r.doctor_out;
      for (const std::string& out : {r.sim_out, r.doctor_out})
        EXPECT_NE(out.find(fmt::format("{} joints ({} moving, 0 fixed): sim_server simulates at most 1000", n, n)),
                  std::string::npos)
            << out;
    }
    figures += fmt::format("{} links: sim_server {} in {:.2f} s; ", n, rc == 0 ? "ready and stepped" : "refused", s);
  }
  std::filesystem::remove_all(folder);
  std::printf("RELIABILITY|limits|serial chains of 500 and 5,000 links|tried=2|ok=%d|crashes=0|hangs=0|%s\n",
              ::testing::Test::HasFailure() ? 0 : 2, figures.c_str());
}

// 20,000 links on fixed joints and one moving joint took 75 s to start: every joint counts against the limit, so
// doctor and sim_server refuse it at once, naming the fixed ones.
TEST(Limits, ManyLinksOnFixedJointsAreRefusedAtOnce) {
  const std::string folder = lt::temp_dir("limits_fixed");
  const auto [urdf, config] = write_chain(folder, 20000, true);
  const Started r = start_sim_and_doctor(urdf, config);
  const double s = r.sim_s;
  EXPECT_EQ(r.doctor_rc, 3) << r.doctor_out;
  EXPECT_EQ(r.sim_rc, 3) << r.sim_out;
  for (const std::string& out : {r.sim_out, r.doctor_out})
    EXPECT_NE(out.find("20000 joints (1 moving, 19999 fixed): sim_server simulates at most 1000"), std::string::npos)
        << out;
  std::filesystem::remove_all(folder);
  std::printf("RELIABILITY|limits|20,000 links on fixed joints|tried=1|ok=%d|crashes=0|hangs=0|refused in %.2f s\n",
              ::testing::Test::HasFailure() ? 0 : 1, s);
}

// Item 1: 5,000 trajectory goals naming a 60 KB joint that clears the screen and forges a line (before: 300 MB of
// log, one raw line per goal). The controller manager's log grows by at most 1 MB per 10,000 such messages, and no
// escape character or forged line reaches it.
TEST(Limits, HostileGoalsCannotFloodOrForgeTheLog) {
  Robot robot;
  ASSERT_NO_FATAL_FAILURE(robot.bring_up());
  sleep_s(0.5);
  const size_t before = robot.cm_output().size();
  lcm::LCM lc(robot.url());
  joint_trajectory_t g = goal_of(1, 1);
  g.joint_names[0] = std::string(60000, 'j') + "\x1b[2J\x1b[31m\r\n[controller_manager] info: all good";
  const int n = 5000;
  for (int k = 0; k < n; ++k) {
    g.goal_id = 100000 + k;
    lc.publish("trajectory_controller/command", &g);
    if (k % 50 == 49) sleep_s(0.005);  // as fast as the bus takes them: 60 KB each
  }
  sleep_s(1.5);
  g.goal_id = 99;  // the next line after the flood tells how many were left out
  lc.publish("trajectory_controller/command", &g);
  sleep_s(0.5);
  const std::string out = robot.cm_output();
  const size_t grew = out.size() - before;
  const double per_10k = double(grew) * 10000.0 / n;
  std::printf("RELIABILITY|limits|%d trajectory goals naming a 60 KB joint with escapes and a forged line|tried=%d|"
              "ok=%d|crashes=0|hangs=0|controller_manager log grew %zu bytes (%.0f bytes per 10,000); escape "
              "characters in it: %zu\n",
              n, n, grew < 500000 ? n : 0, grew, per_10k, size_t(std::count(out.begin(), out.end(), '\x1b')));
  EXPECT_LT(per_10k, 1e6);
  EXPECT_EQ(out.find('\x1b'), std::string::npos);
  EXPECT_EQ(out.find("\n[controller_manager] info: all good"), std::string::npos) << "a forged line";
  EXPECT_NE(out.find("similar lines not logged"), std::string::npos) << out.substr(out.size() - 2000);
}

namespace {

// A whole LCM message ("LC02") on `channel`, as lcm::LCM sends one.
std::vector<uint8_t> lcm_short(uint32_t seqno, const std::string& channel, size_t payload_bytes) {
  std::vector<uint8_t> d = {0x4c, 0x43, 0x30, 0x32, uint8_t(seqno >> 24), uint8_t(seqno >> 16), uint8_t(seqno >> 8),
                            uint8_t(seqno)};
  const std::vector<uint8_t> named = lt::named_payload(channel, payload_bytes);
  d.insert(d.end(), named.begin(), named.end());
  return d;
}

}  // namespace

// Item 3: 100,000 new channel names at 10,000 a second on the shared bus, while sim_server and controller_manager
// (their hardware loop on a URL of its own, so that each reads two), state-logger, `bus list`, the dashboard and
// turret-cmd run. None grows by more than 5 MB per 100,000 names (before: LCM's receive path kept about 300 bytes
// per name for good in every program reading through lcm::LCM: state-logger and `bus list` grew by 36 MB per
// 100,000 names, the dashboard 26, turret-cmd 11).
TEST(Limits, NewChannelNamesDoNotGrowAnyLongRunningProgram) {
  Robot robot;
  // A hardware URL of its own, not `auto`: auto picks a port from the namespace alone, so a robot without one there
  // shared its loop with bench_robots_smoke's lockstep robot whenever the two ran together (launch then refused
  // that robot: "hardware already publishes 'hardware/state' in the default namespace").
  ASSERT_NO_FATAL_FAILURE(robot.bring_up(lt::unique_lcm_url()));
  const std::string dir = lt::temp_dir("limits_names");
  const auto env = robot.env();
  lt::ChildProcess logger({lt::bin("state-logger"), "joint_states", "--output", dir + "/joint_states.csv"}, env);
  lt::ChildProcess list({lt::bin("bus"), "list", "--duration", "100"}, env);
  lt::ChildProcess dash({lt::bin("dashboard"), "--port", "0", "--duration", "100"}, env);
  lt::ChildProcess turret({lt::bin("turret-cmd"), "some/other/channel", "sin(i/100)", "--rate", "60"}, env);
  ASSERT_TRUE(logger.wait_for_output("state-logger: logging", 15)) << logger.output();
  ASSERT_TRUE(dash.wait_for_output("dashboard: http", 15)) << dash.output();
  sleep_s(2.0);  // every program past its start-up allocations
  struct Watched {
    const char* name;
    pid_t pid;
    long before = 0, after = 0;
  };
  std::vector<Watched> programs = {{"sim_server", robot.sim_pid()},  {"controller_manager", robot.controller_manager_pid()},
                                   {"state-logger", logger.pid()},   {"bus list", list.pid()},
                                   {"dashboard", dash.pid()},        {"turret-cmd", turret.pid()}};
  for (auto& p : programs) p.before = lt::rss_kb(p.pid);
  lt::RawSender sender(robot.url());
  const int names = 100000;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < names; ++k) {
    sender.send(lcm_short(uint32_t(k), fmt::format("flood/name_{:07d}_of_a_careless_peer", k), 8));
    if (k % 100 == 99)  // 10,000 a second
      std::this_thread::sleep_until(t0 + std::chrono::microseconds(int64_t(k + 1) * 100));
  }
  sleep_s(2.0);
  int ok = 0, crashes = 0;
  std::string figures = "RSS growth per 100,000 new names:";
  for (auto& p : programs) {
    p.after = lt::rss_kb(p.pid);
    const double per_100k = double(p.after - p.before) * 100000.0 / names;
    figures += fmt::format(" {} {:.0f} kB ({} -> {} kB);", p.name, per_100k, p.before, p.after);
    if (p.after <= 0) {
      ++crashes;
    } else if (per_100k <= 5000) {
      ++ok;
    }
    EXPECT_GT(p.after, 0) << p.name << " is gone";
    EXPECT_LE(per_100k, 5000) << p.name << " grew with the channel names";
  }
  for (auto* c : {&logger, &list, &dash, &turret}) EXPECT_TRUE(c->running()) << c->output();
  std::printf("RELIABILITY|limits|%d new channel names at 10,000/s against 6 long-running programs|tried=6|ok=%d|"
              "crashes=%d|hangs=0|%s\n",
              names, ok, crashes, figures.c_str());
  std::filesystem::remove_all(dir);
}
