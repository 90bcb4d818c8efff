// replay --controllers (open loop): the lockstep demo recorded with `bus record` replays bit for bit; a changed gain
// diverges at the step where it first acts, naming the field and the actuator; a truncated log, a log with no
// hardware in it, a missing configuration, a recording that lost a state and another robot are refused with exit 2,
// naming what to pass. replay --sim (closed loop) re-runs the demo bit for bit, a stiffer simulated PID diverges on
// joint_states, and a log without sim_server's configuration is refused.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>
#include <lcm/lcm-cpp.hpp>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <regex>
#include <string>

#include "lcm_control/run_config_t.hpp"
#include "test/e2e/session.hpp"

namespace lcm_control::testing {
namespace {

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// The lockstep demo (launch's command sources drive j1 and j2) for `seconds`, recorded whole by `bus record`.
std::string record_demo(const std::string& dir, double seconds, const std::vector<std::string>& launch_flags = {}) {
  RobotSession bus(source("config/turret_bot.urdf"), source("config/turret_bot.yaml"));
  const std::string log = dir + "/demo.lcmlog";
  auto recorder = bus.background({"bus", "record", log, "--force"});
  EXPECT_TRUE(recorder->wait_for_output("bus record: recording", 10)) << recorder->output();
  std::string out;
  std::vector<std::string> launch = {"launch", source("config/turret_bot_demo.launch.yaml"), "--duration",
                                     std::to_string(seconds)};
  launch.insert(launch.end(), launch_flags.begin(), launch_flags.end());
  EXPECT_EQ(bus.run(launch, &out, 60), 0) << out;
  EXPECT_EQ(recorder->stop(10), 0) << recorder->output();
  return log;
}

// `log` copied to `out` without the `nth` event on `channel` (0 from the start; -1: every one): a recorder that lost
// that message.
void copy_without(const std::string& log, const std::string& out, const std::string& channel, int nth) {
  lcm::LogFile in(log, "r"), copy(out, "w");
  ASSERT_TRUE(in.good() && copy.good());
  int seen = 0, left_out = 0;
  for (const lcm::LogEvent* e = in.readNextEvent(); e; e = in.readNextEvent()) {
    if (e->channel == channel && (seen++ == nth || nth < 0)) {
      ++left_out;
      continue;
    }
    lcm::LogEvent kept = *e;
    ASSERT_EQ(copy.writeEvent(&kept), 0);
  }
  ASSERT_GT(left_out, 0) << "fewer than " << nth + 1 << " events on " << channel;
}

// `log` copied to `out` with the first event on `channel` written `later_by` events later: a recorder that saw it late.
void copy_moving(const std::string& log, const std::string& out, const std::string& channel, int later_by) {
  lcm::LogFile in(log, "r"), copy(out, "w");
  ASSERT_TRUE(in.good() && copy.good());
  std::optional<lcm::LogEvent> moved;
  std::vector<uint8_t> moved_bytes;
  int after = -1;
  for (const lcm::LogEvent* e = in.readNextEvent(); e; e = in.readNextEvent()) {
    if (!moved && after < 0 && e->channel == channel) {
      moved = *e;
      moved_bytes.assign(static_cast<const uint8_t*>(e->data), static_cast<const uint8_t*>(e->data) + e->datalen);
      moved->data = moved_bytes.data();
      after = 0;
      continue;
    }
    lcm::LogEvent kept = *e;
    ASSERT_EQ(copy.writeEvent(&kept), 0);
    if (moved && ++after == later_by) {
      ASSERT_EQ(copy.writeEvent(&*moved), 0);
      moved.reset();
    }
  }
  ASSERT_GE(after, later_by) << "fewer than " << later_by << " events after the first on " << channel;
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

TEST(ReplayControllers, TheLockstepDemoReplaysBitForBit) {
  const std::string dir = temp_dir("replay_demo");
  const std::string log = record_demo(dir, 3);
  const Replayed same = replay({log, "--controllers"});  // the configuration the run recorded in the log
  std::printf("%s", same.out.c_str());
  EXPECT_EQ(same.rc, 0) << same.out;
  EXPECT_TRUE(has(same.out, "identical: ")) << same.out;
  EXPECT_TRUE(has(same.out, "note: the configuration recorded in the log: " + source("config/turret_bot.urdf") + ", " +
                                source("config/turret_bot.yaml")))
      << same.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(same.out, m, std::regex(R"((\d+) hardware states replayed)"))) << same.out;
  EXPECT_GE(std::stoi(m[1]), 3000);
  ASSERT_TRUE(std::regex_search(same.out, m, std::regex(R"(hardware/command: (\d+) compared, 0 differ)"))) << same.out;
  EXPECT_GE(std::stoi(m[1]), 3000);
  ASSERT_TRUE(std::regex_search(same.out, m, std::regex(R"(joint_states: (\d+) compared, 0 differ)"))) << same.out;
  EXPECT_GE(std::stoi(m[1]), 170);  // the controller's 60 Hz over 3 s
}

// Both robot processes record what they were started with (run_config_t): a recorder started once they run asks
// each for it (CONFIG), so the log holds the URDF as read, the YAML's text and each command line, sim_server's with
// its mode, for a closed-loop replay.
TEST(ReplayControllers, ARecordingStartedLateAsksBothProgramsForWhatTheyWereStartedWith) {
  const std::string dir = temp_dir("replay_configs");
  const std::string urdf = source("config/turret_bot.urdf"), yaml = source("config/turret_bot.yaml");
  const std::string log = dir + "/late.lcmlog";
  {
    LockstepSession robot(urdf, yaml, {});
    ASSERT_NO_FATAL_FAILURE(robot.start({"joint_state_controller", "j1_controller", "j2_controller"}));
    auto recorder = robot.background({"bus", "record", log, "--force", "--duration", "1"});
    EXPECT_EQ(recorder->wait(15), 0) << recorder->output();
    EXPECT_EQ(robot.stop_sim(), 0) << robot.sim_output();
  }
  std::map<std::string, run_config_t> configs;
  lcm::LogFile in(log, "r");
  ASSERT_TRUE(in.good());
  for (const lcm::LogEvent* e = in.readNextEvent(); e; e = in.readNextEvent()) {
    if (e->channel != "controller_manager/config" && e->channel != "sim_server/config") continue;
    run_config_t c;
    ASSERT_EQ(c.decode(e->data, 0, int(e->datalen)), int(e->datalen)) << e->channel;
    configs[e->channel] = c;
  }
  ASSERT_EQ(configs.count("sim_server/config"), 1u) << "sim_server's configuration not in the log";
  ASSERT_EQ(configs.count("controller_manager/config"), 1u);
  const run_config_t& sim = configs["sim_server/config"];
  const run_config_t& cm = configs["controller_manager/config"];
  EXPECT_EQ(sim.process, "sim_server");
  EXPECT_EQ(cm.process, "controller_manager");
  std::ifstream file(urdf);
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  EXPECT_EQ(sim.urdf, text);
  EXPECT_EQ(cm.urdf, text);
  ASSERT_EQ(sim.num_configs, 1);
  EXPECT_EQ(sim.config_paths[0], yaml);
  auto has_flag = [](const run_config_t& c, const std::string& flag, const std::string& value) {
    for (size_t k = 0; k + 1 < c.argv.size(); ++k)
      if (c.argv[k] == flag && c.argv[k + 1] == value) return true;
    return false;
  };
  ASSERT_GT(sim.num_argv, 0);
  EXPECT_TRUE(has(sim.argv[0], "sim_server")) << sim.argv[0];
  EXPECT_TRUE(has_flag(sim, "--mode", "lockstep"));
  EXPECT_TRUE(has_flag(sim, "--urdf", urdf));
  EXPECT_TRUE(has_flag(cm, "--urdf", urdf));
  EXPECT_TRUE(has(cm.argv[0], "controller_manager")) << cm.argv[0];
}

// A chain in the controller manager (a JointTrajectoryController on the references of effort PIDs, ur_like) with a
// goal sent while it runs: the replay is identical; with one PID gain changed it diverges, first at that joint's
// effort command, and says at which step.
TEST(ReplayControllers, AChangedGainDivergesAtTheStepItFirstActs) {
  const std::string dir = temp_dir("replay_gain");
  const std::string urdf = source("test/robots/ur_like.urdf"), yaml = source("test/robots/ur_like_chained.yaml");
  const std::string log = dir + "/chain.lcmlog";
  {
    LockstepSession robot(urdf, yaml, {});
    auto recorder = robot.background({"bus", "record", log, "--force"});
    ASSERT_TRUE(recorder->wait_for_output("bus record: recording", 10)) << recorder->output();
    ASSERT_NO_FATAL_FAILURE(robot.start({"joint_state_broadcaster", "arm_pids", "arm_trajectory"}));
    std::string out;
    ASSERT_EQ(robot.send({"arm_trajectory", "--point", "1:0.2,-0.3,0.4,0.2,0.2,0.2"}, out), 0) << out;
    // The run goes on past the goal's result, so that the result is not among the messages of the recording's
    // last 20 ms, which replay leaves uncompared (stopped right after it, a loaded machine kept it there).
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    EXPECT_EQ(robot.stop_sim(), 0) << robot.sim_output();
    EXPECT_EQ(recorder->stop(10), 0) << recorder->output();
  }
  const Replayed same = replay({log, "--controllers", "--urdf", urdf, "--config", yaml});
  std::printf("%s", same.out.c_str());
  EXPECT_EQ(same.rc, 0) << same.out;
  EXPECT_TRUE(has(same.out, "identical: ")) << same.out;
  EXPECT_TRUE(has(same.out, "note: inputs fed at the cycle the controller manager took them in at")) << same.out;
  EXPECT_TRUE(std::regex_search(same.out, std::regex(R"(arm_trajectory/feedback: [1-9]\d* compared, 0 differ)")))
      << same.out;  // the controllers' outputs too
  EXPECT_TRUE(has(same.out, "arm_trajectory/result: 1 compared, 0 differ")) << same.out;

  // The goal's step is the one the manager stamped (controller_manager/inputs), not the log's order: moved 300 events
  // later (about 150 steps), it still lands where it did; without the stamps, it lands late and the replay diverges.
  const std::string late = dir + "/late_goal.lcmlog", late_unstamped = dir + "/late_goal_unstamped.lcmlog";
  ASSERT_NO_FATAL_FAILURE(copy_moving(log, late, "arm_trajectory/command", 300));
  const Replayed moved = replay({late, "--controllers", "--urdf", urdf, "--config", yaml});
  EXPECT_EQ(moved.rc, 0) << moved.out;
  EXPECT_TRUE(has(moved.out, "identical: ")) << moved.out;
  ASSERT_NO_FATAL_FAILURE(copy_without(late, late_unstamped, "controller_manager/inputs", -1));
  const Replayed unstamped = replay({late_unstamped, "--controllers", "--urdf", urdf, "--config", yaml});
  std::printf("%s", unstamped.out.c_str());
  EXPECT_EQ(unstamped.rc, 1) << unstamped.out;
  EXPECT_TRUE(has(unstamped.out, "note: inputs fed in the log's order (no controller_manager/inputs in it")) << unstamped.out;

  std::string tuned = file_text(yaml);
  const std::string from = "elbow_joint: {p: 2000.0,", to = "elbow_joint: {p: 2500.0,";
  ASSERT_NE(tuned.find(from), std::string::npos);
  tuned.replace(tuned.find(from), from.size(), to);
  const std::string tuned_path = dir + "/ur_like_tuned.yaml";
  std::ofstream(tuned_path) << tuned;
  const Replayed changed = replay({log, "--controllers", "--config", tuned_path});  // the recorded robot, new gains
  std::printf("%s", changed.out.c_str());
  EXPECT_EQ(changed.rc, 1) << changed.out;
  EXPECT_TRUE(std::regex_search(changed.out, std::regex(R"(diverged: first on hardware/command at step \d+ )"
                                                         R"(t=[0-9.]+ s, command\[elbow\w*\]: recorded \S+, )"
                                                         R"(replayed \S+)")))
      << changed.out;

  // A controller's own output: with an elbow goal tolerance it cannot meet, the replayed trajectory controller keeps
  // the goal running where the run reported it done.
  std::string strict = file_text(yaml);
  const std::string tolerance = "elbow_joint: {trajectory: 0.1, goal: 0.02}";
  ASSERT_NE(strict.find(tolerance), std::string::npos);
  strict.replace(strict.find(tolerance), tolerance.size(), "elbow_joint: {trajectory: 0.1, goal: 1.0e-9}");
  const std::string strict_path = dir + "/ur_like_strict.yaml";
  std::ofstream(strict_path) << strict;
  const Replayed outputs = replay({log, "--controllers", "--config", strict_path});
  std::printf("%s", outputs.out.c_str());
  EXPECT_EQ(outputs.rc, 1) << outputs.out;
  EXPECT_TRUE(std::regex_search(outputs.out, std::regex(R"(diverged: first on arm_trajectory/(feedback|result) at )"
                                                         R"(t=[0-9.]+ s, (\(a message the (run|replay) published|)"
                                                         R"(utime \(published at another time\)))")))
      << outputs.out;
}

// A real-time run (sim_server paced by the wall clock, the goal taken in on the intake's thread) replays open loop
// within the tolerance the guide states; bit for bit is not promised there.
TEST(ReplayControllers, ARealTimeRecordingReplaysWithinItsTolerance) {
  const std::string dir = temp_dir("replay_real_time");
  const std::string urdf = source("test/robots/ur_like.urdf"), yaml = source("test/robots/ur_like_chained.yaml");
  const std::string log = dir + "/real_time.lcmlog";
  {
    RobotSession robot(urdf, yaml);
    auto recorder = robot.background({"bus", "record", log, "--force"});
    ASSERT_TRUE(recorder->wait_for_output("bus record: recording", 10)) << recorder->output();
    robot.start_controller_manager();
    ASSERT_NO_FATAL_FAILURE(robot.spawn({"joint_state_broadcaster", "arm_pids", "arm_trajectory"}));
    ASSERT_NO_FATAL_FAILURE(robot.start_sim({}, 30));
    std::string out;
    ASSERT_EQ(robot.run({"send-trajectory", "arm_trajectory", "--point", "0.5:0.2,-0.3,0.4,0.2,0.2,0.2"}, &out, 30), 0)
        << out;
    EXPECT_EQ(recorder->stop(10), 0) << recorder->output();
  }
  const Replayed r = replay({log, "--controllers", "--tolerance", "1e-6"});
  std::printf("%s", r.out.c_str());
  EXPECT_EQ(r.rc, 0) << r.out;
  EXPECT_TRUE(has(r.out, "within tolerance 1e-06: ")) << r.out;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.out, m, std::regex(R"(hardware/command: (\d+) compared)"))) << r.out;
  EXPECT_GE(std::stoi(m[1]), 250);  // the 0.5 s goal at 500 Hz
}

TEST(ReplayControllers, BadInputIsRefusedWithExitTwoNamingWhatToPass) {
  const std::string dir = temp_dir("replay_bad_input");
  const std::string log = record_demo(dir, 1);
  const std::string urdf = source("config/turret_bot.urdf"), yaml = source("config/turret_bot.yaml");

  // Recorded with every input but without the controller manager's configuration: refused, saying what to pass.
  const std::string bare = dir + "/bare.lcmlog";
  {
    RobotSession robot(urdf, yaml);
    auto recorder = robot.background({"bus", "record", bare, "--force", "-c",
                                      "hardware/.*|joint_states|controller_manager/(request|command_source)|j[12]_controller/.*"});
    EXPECT_TRUE(recorder->wait_for_output("bus record: recording", 10)) << recorder->output();
    std::string out;
    EXPECT_EQ(robot.run({"launch", source("config/turret_bot_demo.launch.yaml"), "--duration", "0.5"}, &out, 60), 0)
        << out;
    EXPECT_EQ(recorder->stop(10), 0) << recorder->output();
  }
  const Replayed no_config = replay({bare, "--controllers"});
  EXPECT_EQ(no_config.rc, 2) << no_config.out;
  EXPECT_TRUE(has(no_config.out, "bare.lcmlog: this log carries no recorded configuration (no "
                                 "controller_manager/config message: recorded without that channel, or by a version "
                                 "before it); give the run's robot and controllers with --urdf FILE --config FILE"))
      << no_config.out;
  EXPECT_EQ(replay({bare, "--controllers", "--urdf", urdf, "--config", yaml}).rc, 0) << "given, it replays";

  const std::string cut = dir + "/cut.lcmlog";
  {
    std::ifstream in(log, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2 + 7);
  }
  const Replayed truncated = replay({cut, "--controllers", "--urdf", urdf, "--config", yaml});
  EXPECT_EQ(truncated.rc, 2) << truncated.out;
  EXPECT_TRUE(has(truncated.out, "cut.lcmlog: truncated or corrupted after event ")) << truncated.out;
  // 100 bytes overwritten from an event's start in the middle: its framing is gone. (A log has no checksum: bytes
  // garbled inside a message that still decodes are a divergence, exit 1, not bad input.)
  const std::string garbled = dir + "/garbled.lcmlog";
  {
    std::ifstream in(log, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const size_t event = bytes.find("\xED\xA1\xDA\x01", bytes.size() / 2);
    ASSERT_NE(event, std::string::npos);
    bytes.replace(event, 100, std::string(100, 'Z'));
    std::ofstream(garbled, std::ios::binary) << bytes;
  }
  const Replayed corrupted = replay({garbled, "--controllers", "--urdf", urdf, "--config", yaml});
  EXPECT_EQ(corrupted.rc, 2) << corrupted.out;
  EXPECT_TRUE(std::regex_search(corrupted.out, std::regex(R"(garbled.lcmlog: (truncated or corrupted after event \d+ )"
                                                           R"(\(byte \d+ of \d+\)|event \d+ on '[^']+' does not decode))")))
      << corrupted.out;
  // 16 bytes slipped in between two events: the log ends there, as liblcm ends it ("Invalid header after log data").
  const std::string gap = dir + "/gap.lcmlog";
  {
    std::ifstream in(log, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes.insert(bytes.find("\xED\xA1\xDA\x01", bytes.size() / 2), std::string(16, '\0'));
    std::ofstream(gap, std::ios::binary) << bytes;
  }
  const Replayed gapped = replay({gap, "--controllers", "--urdf", urdf, "--config", yaml});
  EXPECT_EQ(gapped.rc, 2) << gapped.out;
  EXPECT_TRUE(has(gapped.out, "gap.lcmlog: truncated or corrupted after event ")) << gapped.out;

  // A recorder that lost a state lost an input: refused, naming the step. One that lost a command lost only what is
  // compared: the rest is compared and the loss counted.
  const std::string lost_state = dir + "/lost_state.lcmlog", lost_command = dir + "/lost_command.lcmlog";
  copy_without(log, lost_state, "hardware/state", 500);
  const Replayed no_state = replay({lost_state, "--controllers"});
  EXPECT_EQ(no_state.rc, 2) << no_state.out;
  EXPECT_TRUE(std::regex_search(no_state.out, std::regex(R"(lost_state.lcmlog: the recording lost the hardware/state )"
                                                          R"(of step \d+ \(event \d+ is the controller manager's )"
                                                          R"(answer to it)")))
      << no_state.out;
  copy_without(log, lost_command, "hardware/command", 500);
  const Replayed no_command = replay({lost_command, "--controllers"});
  EXPECT_EQ(no_command.rc, 0) << no_command.out;
  EXPECT_TRUE(has(no_command.out, "1 answer(s) to recorded states have no hardware/command in the log")) << no_command.out;

  const Replayed other_robot =
      replay({log, "--controllers", "--urdf", source("test/robots/gripper.urdf"), "--config",
              source("test/robots/gripper_action.yaml")});
  EXPECT_EQ(other_robot.rc, 2) << other_robot.out;
  EXPECT_TRUE(has(other_robot.out, "the recorded robot is not ")) << other_robot.out;
  EXPECT_TRUE(has(other_robot.out, "actuator 'finger_motor' (joint 'left_finger_joint') is missing")) << other_robot.out;

  const std::string empty = dir + "/no_hardware.lcmlog";
  {
    RobotSession quiet(urdf, yaml);
    auto recorder = quiet.background({"bus", "record", empty, "--force", "--duration", "0.3"});
    EXPECT_EQ(recorder->wait(10), 0) << recorder->output();
  }
  const Replayed nothing = replay({empty, "--controllers", "--urdf", urdf, "--config", yaml});
  EXPECT_EQ(nothing.rc, 2) << nothing.out;
  EXPECT_TRUE(has(nothing.out, "no hardware/state messages")) << nothing.out;
}

// replay --sim (closed loop): the simulation re-runs too, from sim_server's recorded configuration.
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

TEST(ReplaySim, ALogWithoutSimServersConfigurationOrInRealTimeIsRefusedSayingWhy) {
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
  // Another robot than the log's: refused, naming the first actuator (and its joint) that does not match.
  const Replayed other = replay({log, "--sim", "--urdf", source("test/robots/gripper.urdf"), "--config",
                                 source("test/robots/gripper_action.yaml")});
  EXPECT_EQ(other.rc, 2) << other.out;
  EXPECT_TRUE(has(other.out, "the recorded robot is not ")) << other.out;
  EXPECT_TRUE(has(other.out, "actuator 'finger_motor' (joint 'left_finger_joint') is missing")) << other.out;
  // A real-time recording: its cycles followed the wall clock; open loop is what replays it.
  const std::string real_time = record_demo(temp_dir("replay_sim_real_time"), 1, {"--mode", "realtime"});
  const Replayed rt = replay({real_time, "--sim"});
  EXPECT_EQ(rt.rc, 2) << rt.out;
  EXPECT_TRUE(has(rt.out, "recorded in real time (sim_server --mode realtime)")) << rt.out;
  EXPECT_TRUE(has(rt.out, "--controllers")) << rt.out;
}

}  // namespace
}  // namespace lcm_control::testing
