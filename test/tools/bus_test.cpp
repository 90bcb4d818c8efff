// Messages as text (tools/message_text) and the bus program: list, hz, echo,
// pub, types, record and info on a private LCM URL, against messages this test
// sends.
#include <gtest/gtest.h>

#include <fmt/format.h>

#include <atomic>
#include <functional>
#include <thread>

#include "lcm_control/e_stop_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"
#include "tools/lib/messages/fields.hpp"
#include "tools/lib/messages/message_text.hpp"

namespace lt = lcm_control::testing;
using namespace lcm_control;
using namespace lcm_control::tools;

namespace {

template <class Msg>
Msg decoded(const std::vector<uint8_t>& bytes) {
  Msg m;
  EXPECT_EQ(m.decode(bytes.data(), 0, int(bytes.size())), int(bytes.size()));
  return m;
}

template <class Msg>
std::vector<uint8_t> encoded(const Msg& m) {
  std::vector<uint8_t> b(size_t(m.getEncodedSize()));
  m.encode(b.data(), 0, int(b.size()));
  return b;
}

std::string build_error(const std::string& type, const std::vector<std::string>& fields) {
  try {
    build_message(type, fields, 0);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(MessageText, BuildsNestedMessagesWithCountsFromTheArrays) {
  const auto t = decoded<joint_trajectory_t>(build_message(
      "joint_trajectory", {"joint_names=[j1, j2]", "points[1].positions=[1,2]", "points[0].positions=[0.5, 1.0]",
                           "points[0].time_from_start=2", "points[1].time_from_start=3", "goal_id=7"},
      42));
  EXPECT_EQ(t.utime, 42);  // not assigned: the default
  EXPECT_EQ(t.goal_id, 7);
  EXPECT_EQ(t.num_joints, 2);
  EXPECT_EQ(t.joint_names, (std::vector<std::string>{"j1", "j2"}));
  ASSERT_EQ(t.num_points, 2);
  EXPECT_EQ(t.points[0].positions, (std::vector<double>{0.5, 1.0}));
  EXPECT_EQ(t.points[0].num_positions, 2);
  EXPECT_EQ(t.points[1].time_from_start, 3);
  EXPECT_EQ(t.points[1].num_velocities, 0);
}

TEST(MessageText, ElementsMatricesBooleansAndAnExplicitUtime) {
  const auto p = decoded<link_poses_t>(build_message(
      "lcm_control.link_poses_t",
      {"name[1]=b", "name[0]=a", "position[1][2]=5", "position[0]=[1,2,3]", "orientation[1]=[1,0,0,0]",
       "orientation[0][0]=1", "utime=9"},
      42));
  EXPECT_EQ(p.utime, 9);
  EXPECT_EQ(p.num_links, 2);
  EXPECT_EQ(p.position, (std::vector<std::vector<double>>{{1, 2, 3}, {0, 0, 5}}));
  EXPECT_EQ(p.orientation[0], (std::vector<double>{1, 0, 0, 0}));
  const auto e = decoded<e_stop_t>(build_message("e_stop_t", {"engaged=true", "source=a b, c"}, 0));
  EXPECT_EQ(e.engaged, 1);
  EXPECT_EQ(e.source, "a b, c");
}

TEST(MessageText, ErrorsNameTheTypeTheFieldAndTheFields) {
  EXPECT_NE(build_error("float64_t", {"dat=1"}).find("float64_t: dat: no such field; its fields: utime (int64), data "
                                                     "(double)"),
            std::string::npos);
  EXPECT_NE(build_error("joint_state_t", {"name=[a,b]", "position=[1]"}).find("position has 1 values but name has 2"),
            std::string::npos);
  EXPECT_NE(build_error("joint_state_t", {"num_joints=3"}).find("set from the length of the arrays"),
            std::string::npos);
  EXPECT_NE(build_error("float64_t", {"data=abc"}).find("'abc' is not a number"), std::string::npos);
  EXPECT_NE(build_error("e_stop_t", {"engaged=300"}).find("out of range"), std::string::npos);
  EXPECT_NE(build_error("float64_t", {"data"}).find("is not FIELD=VALUE"), std::string::npos);
  EXPECT_NE(build_error("joint_trajectory_t", {"points[0]=1"}).find("points[K].FIELD=VALUE"), std::string::npos);
  EXPECT_NE(build_error("joint_trajectory_t", {"points[0].nope=1"}).find("no field 'nope' in trajectory_point_t"),
            std::string::npos);
  EXPECT_NE(build_error("link_poses_t", {"position[0]=[1,2]"}).find("rows have 3"), std::string::npos);
  EXPECT_NE(build_error("nosuch_t", {}).find("unknown message type 'nosuch_t'; the types are: ackermann_drive_t, activity_t, cm_inputs_t"),
            std::string::npos);
}

TEST(MessageText, YamlShowsEveryFieldAndQuotesStringsThatNeedIt) {
  joint_trajectory_t t{};
  t.utime = 5;
  t.num_joints = 2;
  t.joint_names = {"j1", "a: b"};
  t.num_points = 1;
  t.points.resize(1);
  t.points[0].time_from_start = 1.5;
  t.points[0].num_positions = 2;
  t.points[0].positions = {0.25, -1};
  const auto b = encoded(t);
  EXPECT_EQ(message_yaml(b.data(), b.size()),
            "utime: 5\ngoal_id: 0\njoint_names: [j1, \"a: b\"]\npoints:\n- time_from_start: 1.5\n"
            "  positions: [0.25, -1]\n  velocities: []\n  accelerations: []\n");
  EXPECT_THROW(message_yaml(b.data(), 4), std::runtime_error);
  std::vector<uint8_t> cut(b.begin(), b.begin() + 20);
  EXPECT_THROW(message_yaml(cut.data(), cut.size()), std::runtime_error);
}

TEST(MessageText, EveryTypeBuildsAndReadsBack) {
  // Built with only its utime (if any), every type encodes, decodes by fingerprint, and prints.
  for (const auto& type : message_type_names()) {
    const auto b = build_message(type, {}, 1);
    EXPECT_EQ(type_of_payload(b.data(), b.size()), "lcm_control." + type);
    EXPECT_NO_THROW(message_yaml(b.data(), b.size())) << type;
    EXPECT_FALSE(message_fields(type).empty()) << type;
  }
}

// --- the program ------------------------------------------------------------------------------------------------

namespace {

// Publishes on the bus every period_ms until destroyed: a float64_t on `channel` (data 0.5, 1, 1.5, ...), or what
// `publish` sends.
class Ticker {
 public:
  Ticker(const std::string& url, int period_ms, std::function<void(lcm::LCM&)> publish) : lc_(url) {
    thread_ = std::thread([this, period_ms, publish] {
      while (!stop_) {
        publish(lc_);
        std::this_thread::sleep_for(std::chrono::milliseconds(period_ms));
      }
    });
  }
  Ticker(const std::string& url, std::string channel, int period_ms)
      : Ticker(url, period_ms, [channel, m = float64_t{}](lcm::LCM& lc) mutable {
          m.utime += 1000;
          m.data += 0.5;
          lc.publish(channel, &m);
        }) {}
  ~Ticker() {
    stop_ = true;
    thread_.join();
  }

 private:
  lcm::LCM lc_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

std::map<std::string, std::string> env(const std::string& url) { return {{"LCM_DEFAULT_URL", url}}; }

}  // namespace

TEST(BusTool, ListHzAndEchoSeeWhatIsOnTheBus) {
  const std::string url = lt::unique_lcm_url();
  Ticker fast(url, "robot/fast", 5), slow(url, "robot/slow", 100);
  lt::ChildProcess list({lt::bin("bus"), "list", "--duration", "1.5"}, env(url));
  ASSERT_EQ(list.wait(20), 0) << list.output();
  EXPECT_NE(list.output().find("robot/fast"), std::string::npos) << list.output();
  EXPECT_NE(list.output().find("lcm_control.float64_t"), std::string::npos) << list.output();
  EXPECT_NE(list.output().find("2 channels over"), std::string::npos) << list.output();

  lt::ChildProcess hz({lt::bin("bus"), "hz", "/robot/fast", "--duration", "2.2"}, env(url));
  ASSERT_EQ(hz.wait(20), 0) << hz.output();
  const auto at = hz.output().find("average rate: ");
  ASSERT_NE(at, std::string::npos) << hz.output();
  const double rate = std::stod(hz.output().substr(at + 14));
  EXPECT_GT(rate, 80);  // 5 ms period plus the publisher's own time: under 200 Hz, well over 80
  EXPECT_LT(rate, 205);
  EXPECT_EQ(hz.output().find("no new messages"), std::string::npos) << "the last line is the run's: " << hz.output();
  EXPECT_NE(hz.output().find(" messages in 2.2 s ("), std::string::npos) << hz.output();

  lt::ChildProcess echo({lt::bin("bus"), "--namespace", "robot", "echo", "slow", "--count", "2"}, env(url));
  ASSERT_EQ(echo.wait(20), 0) << echo.output();
  EXPECT_NE(echo.output().find("utime: "), std::string::npos) << echo.output();
  EXPECT_NE(echo.output().find("data: "), std::string::npos) << echo.output();

  lt::ChildProcess csv({lt::bin("bus"), "echo", "robot/slow", "--count", "1", "--csv"}, env(url));
  ASSERT_EQ(csv.wait(20), 0) << csv.output();
  EXPECT_NE(csv.output().find("utime,data\n"), std::string::npos) << csv.output();
}

TEST(BusTool, NothingOnTheChannelExits4AndListsWhatWasSeen) {
  const std::string url = lt::unique_lcm_url();
  Ticker other(url, "joint_states_typo", 10);
  lt::ChildProcess echo({lt::bin("bus"), "echo", "/joint_states", "--duration", "1"}, env(url));
  EXPECT_EQ(echo.wait(20), 4) << echo.output();
  EXPECT_NE(echo.output().find("no message on 'joint_states'"), std::string::npos) << echo.output();
  EXPECT_NE(echo.output().find("channels seen: joint_states_typo"), std::string::npos) << echo.output();
  lt::ChildProcess hz({lt::bin("bus"), "hz", "nothing", "--duration", "1"}, env(url));
  EXPECT_EQ(hz.wait(20), 4) << hz.output();
  const std::string quiet = lt::unique_lcm_url();
  lt::ChildProcess list({lt::bin("bus"), "list", "--duration", "0.5"}, env(quiet));
  EXPECT_EQ(list.wait(20), 4) << list.output();
  EXPECT_NE(list.output().find("no messages on"), std::string::npos) << list.output();
}

// A hardware loop in shared memory is not on LCM: bus names the mirror instead of failing to open "shm:..." as a URL.
TEST(BusTool, AHardwareLoopInSharedMemoryIsRefusedNamingTheMirror) {
  lt::ChildProcess hz({lt::bin("bus"), "hz", "hardware/state", "--hardware-url", "shm", "--duration", "1"},
                      env(lt::unique_lcm_url()));
  EXPECT_EQ(hz.wait(20), 4) << hz.output();
  EXPECT_NE(hz.output().find("--hardware-url shm: bus reads LCM"), std::string::npos) << hz.output();
  EXPECT_NE(hz.output().find("--hardware-mirror HZ"), std::string::npos) << hz.output();
}

TEST(BusTool, EchoPrintsOneFieldByRosPathOrDashboardLabelAndSuggestsTheNearestForATypo) {
  const std::string url = lt::unique_lcm_url();
  Ticker states(url, 10, [](lcm::LCM& lc) {
    joint_state_t js{};
    js.utime = 7;
    js.num_joints = 2;
    js.name = {"j1", "j2"};
    js.position = {0.25, -1.5};
    js.velocity = {0, 2};
    js.effort = {0, 0};
    lc.publish("joint_states", &js);
  });
  lt::ChildProcess ros({lt::bin("bus"), "echo", "/joint_states/position", "--count", "1"}, env(url));
  ASSERT_EQ(ros.wait(20), 0) << ros.output();
  EXPECT_EQ(ros.output(), "position[j1]: 0.25\nposition[j2]: -1.5\n---\n");
  for (const std::string field : {"position[j2]", "position[1]", "/position[j2]"}) {
    lt::ChildProcess one({lt::bin("bus"), "echo", "joint_states", "--field", field, "--count", "1"}, env(url));
    ASSERT_EQ(one.wait(20), 0) << field << "\n" << one.output();
    EXPECT_EQ(one.output(), "-1.5\n---\n") << field;
  }
  lt::ChildProcess csv({lt::bin("bus"), "echo", "joint_states", "--field", "velocity[j2]", "--csv", "--count", "1"},
                       env(url));
  ASSERT_EQ(csv.wait(20), 0) << csv.output();
  EXPECT_EQ(csv.output(), "utime,velocity[1]\n7,2\n");

  lt::ChildProcess two({lt::bin("bus"), "echo", "joint_states", "--field", "position[j2]", "--field", "velocity[j2]",
                        "--count", "1"},
                       env(url));
  ASSERT_EQ(two.wait(20), 0) << two.output();
  EXPECT_EQ(two.output(), "position[j2]: -1.5\nvelocity[j2]: 2\n---\n");
  lt::ChildProcess two_csv({lt::bin("bus"), "echo", "joint_states", "--field", "position[j1]", "--field",
                            "velocity[j2]", "--csv", "--count", "1"},
                           env(url));
  ASSERT_EQ(two_csv.wait(20), 0) << two_csv.output();
  EXPECT_EQ(two_csv.output(), "utime,position[0],velocity[1]\n7,0.25,2\n");

  lt::ChildProcess typo({lt::bin("bus"), "echo", "joint_states", "--field", "postion[j2]", "--duration", "5"},
                        env(url));
  EXPECT_EQ(typo.wait(20), 1) << typo.output();
  EXPECT_NE(typo.output().find("bus: error: joint_states messages (lcm_control.joint_state_t) have no field "
                               "'postion[j2]'; nearest: position[j2], position[j1], position[0], position[1], "
                               "position\n"),
            std::string::npos)
      << typo.output();
  lt::ChildProcess ros_typo({lt::bin("bus"), "echo", "/joint_states/postion", "--duration", "5"}, env(url));
  EXPECT_EQ(ros_typo.wait(20), 1) << ros_typo.output();
  EXPECT_NE(ros_typo.output().find("have no field 'postion'; nearest: position"), std::string::npos)
      << ros_typo.output();
}

TEST(BusTool, PlayReplaysALogAtItsPaceScaledBySpeedLoopsAndStopsAtCtrlC) {
  const std::string dir = lt::temp_dir("bus_play");
  {
    lt::TestLog log(dir + "/run.lcmlog");
    for (int k = 0; k < 11; ++k) {
      float64_t m{};
      m.utime = k;
      m.data = k * 0.5;
      log.put_message(k % 2 ? "j1/command" : "j2/command", k * 100000, m);  // 1 s of messages
    }
  }
  const std::string url = lt::unique_lcm_url();
  lcm::LCM lc(url);
  lt::Recorder<float64_t> j1(lc, "j1/command"), j2(lc, "j2/command");
  const auto start = std::chrono::steady_clock::now();
  lt::ChildProcess once({lt::bin("bus"), "play", dir + "/run.lcmlog", "--speed", "4", "--lcm-url", url});
  ASSERT_EQ(once.wait(20), 0) << once.output();
  const double took = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(took, 0.25 * 0.95) << "1 s of log at 4x real time";
  EXPECT_NE(once.output().find("bus play: 11 messages on 2 channels"), std::string::npos) << once.output();
  ASSERT_TRUE(lt::pump_until(lc, [&] { return j1.messages.size() + j2.messages.size() >= 11; }, 5));
  ASSERT_EQ(j2.messages.size(), 6u);
  for (size_t k = 0; k < j2.messages.size(); ++k) EXPECT_EQ(j2.messages[k].utime, int64_t(2 * k));

  lt::ChildProcess looped({lt::bin("bus"), "play", dir + "/run.lcmlog", "-s", "20", "--loop", "--duration", "0.5",
                           "--lcm-url", url});
  ASSERT_EQ(looped.wait(20), 0) << looped.output();
  EXPECT_NE(looped.output().find(" passes)"), std::string::npos) << "1 s at 20x, for 0.5 s\n" << looped.output();

  lt::ChildProcess endless({lt::bin("bus"), "play", dir + "/run.lcmlog", "--loop", "--lcm-url", url});
  ASSERT_TRUE(endless.wait_for_output("looping until Ctrl-C", 10)) << endless.output();
  EXPECT_EQ(endless.stop(10), 0) << endless.output();
  EXPECT_NE(endless.output().find("bus play: "), std::string::npos) << endless.output();

  lt::ChildProcess missing({lt::bin("bus"), "play", dir + "/none.lcmlog", "--lcm-url", url});
  EXPECT_EQ(missing.wait(20), 3) << missing.output();
  lt::ChildProcess still({lt::bin("bus"), "play", dir + "/run.lcmlog", "--speed", "0", "--lcm-url", url});
  EXPECT_EQ(still.wait(20), 2) << still.output();
}

TEST(BusTool, PubSendsWhatEchoAndAReceiverRead) {
  const std::string url = lt::unique_lcm_url();
  lcm::LCM lc(url);
  lt::Recorder<e_stop_t> stops(lc, "e_stop");
  lt::ChildProcess pub({lt::bin("bus"), "pub", "/e_stop", "e_stop_t", "engaged=true", "source=bus test"}, env(url));
  ASSERT_EQ(pub.wait(20), 0) << pub.output();
  ASSERT_TRUE(lt::pump_until(lc, [&] { return !stops.messages.empty(); }, 5));
  EXPECT_EQ(stops.messages[0].engaged, 1);
  EXPECT_EQ(stops.messages[0].source, "bus test");
  EXPECT_GT(stops.messages[0].utime, 0);

  lt::Recorder<float64_t> cmds(lc, "j1/command");
  lt::ChildProcess rated({lt::bin("bus"), "pub", "j1/command", "float64", "data=0.5", "--rate", "100", "--count", "5"},
                         env(url));
  ASSERT_EQ(rated.wait(20), 0) << rated.output();
  ASSERT_TRUE(lt::pump_until(lc, [&] { return cmds.messages.size() >= 5; }, 5));
  EXPECT_EQ(cmds.messages[4].data, 0.5);

  lt::ChildProcess bad({lt::bin("bus"), "pub", "x", "float64_t", "dat=1"}, env(url));
  EXPECT_EQ(bad.wait(20), 2) << bad.output();
  EXPECT_NE(bad.output().find("no such field; its fields: utime (int64), data (double)"), std::string::npos)
      << bad.output();
}

TEST(BusTool, InfoSummarisesALogAndRefusesWhatIsNotOne) {
  const std::string dir = lt::temp_dir("bus_info");
  {
    lt::TestLog log(dir + "/run.lcmlog");
    float64_t m{};
    for (int k = 0; k < 11; ++k) log.put_message("j1/command", k * 100000, m);
    log.put("raw", 0, {1, 2, 3});
  }
  lt::ChildProcess info({lt::bin("bus"), "info", dir + "/run.lcmlog"});
  ASSERT_EQ(info.wait(20), 0) << info.output();
  EXPECT_NE(info.output().find("duration:  1.000 s"), std::string::npos) << info.output();
  EXPECT_NE(info.output().find("messages:  12"), std::string::npos) << info.output();
  EXPECT_NE(info.output().find("11 msgs       10.0 Hz  lcm_control.float64_t"), std::string::npos) << info.output();
  EXPECT_NE(info.output().find("? (3 bytes)"), std::string::npos) << info.output();

  lt::ChildProcess folder({lt::bin("bus"), "info", dir});
  EXPECT_EQ(folder.wait(20), 3) << folder.output();
  EXPECT_NE(folder.output().find(dir + ": not a regular file"), std::string::npos) << folder.output();
  lt::ChildProcess missing({lt::bin("bus"), "info", dir + "/none.lcmlog"});
  EXPECT_EQ(missing.wait(20), 3) << missing.output();
}

// A burst at several thousand messages a second, which lcm-logger's queue of 30 cannot ride out if it loses the
// CPU for a few ms: every matching message lands in the log, in order, with its bytes; Ctrl-C ends it cleanly.
TEST(BusTool, RecordKeepsEveryMessageOfABurstInLcmLoggersFormat) {
  const std::string dir = lt::temp_dir("bus_record");
  const std::string url = lt::unique_lcm_url() + "&recv_buf_size=4194304";
  const std::string path = dir + "/burst.lcmlog";
  lt::ChildProcess rec({lt::bin("bus"), "record", path, "-c", "joint_states|j2/command"}, env(url));
  ASSERT_TRUE(rec.wait_for_output("bus record: recording", 15)) << rec.output();
  constexpr int kMessages = 5000;
  {
    lcm::LCM lc(url);
    float64_t m{};
    for (int k = 0; k < kMessages; ++k) {
      m.utime = k;
      m.data = k * 0.25;
      lc.publish(k % 2 ? "j2/command" : "joint_states", &m);
      lc.publish("not_recorded", &m);
      if (k % 10 == 9) std::this_thread::sleep_for(std::chrono::microseconds(1000));
    }
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ASSERT_EQ(rec.stop(10), 0) << rec.output();
  EXPECT_NE(rec.output().find(fmt::format("bus record: {} messages on 2 channels", kMessages)), std::string::npos)
      << rec.output();

  lcm::LogFile log(path, "r");
  ASSERT_TRUE(log.good());
  int n = 0;
  int64_t last_time = 0;
  for (const lcm::LogEvent* e = log.readNextEvent(); e; e = log.readNextEvent(), ++n) {
    ASSERT_EQ(e->channel, n % 2 ? "j2/command" : "joint_states") << "event " << n;
    float64_t m{};
    ASSERT_EQ(m.decode(e->data, 0, e->datalen), e->datalen);
    EXPECT_EQ(m.utime, n);
    EXPECT_EQ(e->eventnum, n);
    EXPECT_GE(e->timestamp, last_time);
    last_time = e->timestamp;
  }
  EXPECT_EQ(n, kMessages);

  lt::ChildProcess again({lt::bin("bus"), "record", path, "--duration", "0.2"}, env(url));
  EXPECT_EQ(again.wait(20), 2) << again.output();
  EXPECT_NE(again.output().find("exists: give --force to overwrite it"), std::string::npos) << again.output();
  lt::ChildProcess forced({lt::bin("bus"), "record", path, "--force", "--duration", "0.2"}, env(url));
  EXPECT_EQ(forced.wait(20), 0) << forced.output();
  EXPECT_NE(forced.output().find("bus record: 0 messages on 0 channels"), std::string::npos) << forced.output();
}

TEST(BusTool, TypesListsTypesAndFields) {
  lt::ChildProcess types({lt::bin("bus"), "types"});
  ASSERT_EQ(types.wait(20), 0) << types.output();
  EXPECT_NE(types.output().find("joint_trajectory_t\n"), std::string::npos);
  lt::ChildProcess fields({lt::bin("bus"), "types", "joint_trajectory_t"});
  ASSERT_EQ(fields.wait(20), 0) << fields.output();
  EXPECT_NE(fields.output().find("points[].positions[] (double)"), std::string::npos) << fields.output();
}

// Two netchecks on one URL hear each other (here both on this computer, over loopback); a lone one exits 4 and says
// what to do. The URL's ttl=0 is reported as keeping everything on this computer.
TEST(BusTool, NetcheckFindsTheOtherNetcheckAndSaysWhenNoneAnswers) {
  const std::string url = lt::unique_lcm_url();
  lt::ChildProcess answerer({lt::bin("bus"), "netcheck", "--answer", "--duration", "6"}, env(url));
  ASSERT_TRUE(answerer.wait_for_output("host:", 5)) << answerer.output();
  lt::ChildProcess checker({lt::bin("bus"), "netcheck", "--duration", "2"}, env(url));
  EXPECT_EQ(checker.wait(10), 0) << checker.output();
  const std::string pid = std::to_string(answerer.pid());
  EXPECT_NE(checker.output().find("pid " + pid + ": answered our probe (both ways work)"), std::string::npos)
      << checker.output();
  EXPECT_NE(checker.output().find("ttl:       0: nothing leaves this computer"), std::string::npos)
      << checker.output();
  EXPECT_NE(checker.output().find("route:     multicast to 239.255.76.67 leaves by lo"), std::string::npos)
      << checker.output();
  EXPECT_NE(answerer.output().find("peer:      "), std::string::npos) << answerer.output();

  lt::ChildProcess lone({lt::bin("bus"), "netcheck", "--duration", "1"}, env(lt::unique_lcm_url()));
  EXPECT_EQ(lone.wait(10), 4) << lone.output();
  EXPECT_NE(lone.output().find("bus: error: no other netcheck answered on udpm://"), std::string::npos)
      << lone.output();
  EXPECT_NE(lone.output().find("with ttl=0 only programs on this computer can answer"), std::string::npos)
      << lone.output();
}

// Nothing on the channel in this namespace, but the channel heard under another: the hint comes at once, while bus
// keeps listening (issue 32, item 2).
TEST(BusTool, AChannelHeardOnlyUnderAnotherNamespaceIsNamedAtOnce) {
  const std::string url = lt::unique_lcm_url();
  Ticker other(url, "rrbot/joint_states", 10);
  lt::ChildProcess echo({lt::bin("bus"), "echo", "joint_states", "--duration", "1.5"}, env(url));
  EXPECT_EQ(echo.wait(20), 4) << echo.output();
  EXPECT_NE(echo.output().find("bus: no message on 'joint_states'; 'rrbot/joint_states' is heard under namespace "
                               "'rrbot': did you mean --namespace rrbot?\n"),
            std::string::npos)
      << echo.output();
  lt::ChildProcess hz({lt::bin("bus"), "hz", "joint_states", "--duration", "1.5"},
                      {{"LCM_DEFAULT_URL", url}, {"LCM_CONTROL_NAMESPACE", "rrbot"}});
  EXPECT_EQ(hz.wait(20), 0) << "the namespace from the environment\n" << hz.output();
}
