// The tools against the real sim_server and controller_manager: launch up and
// down (pids checked), a child's death, the tutorial's ROS launch file, tune's
// effect on the step response, and turret-cmd --sim-time under lockstep (exact).
#include <gtest/gtest.h>
#include <sched.h>
#include <signal.h>

#include <cerrno>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>

#include "lcm_control/float64_t.hpp"
#include "lcm_control/hardware_command_t.hpp"
#include "lcm_control/joint_state_t.hpp"
#include "lcm_control/link_poses_t.hpp"
#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control;
using namespace lcm_control::testing;

namespace {

// "[launch] started NAME (pid N)" lines.
std::map<std::string, pid_t> started_pids(const std::string& out) {
  std::map<std::string, pid_t> pids;
  const std::regex re(R"(\[launch\] started (\S+) \(pid (\d+)\))");
  for (auto it = std::sregex_iterator(out.begin(), out.end(), re); it != std::sregex_iterator(); ++it)
    pids[(*it)[1]] = pid_t(std::stoi((*it)[2]));
  return pids;
}

bool gone(pid_t pid) { return kill(pid, 0) != 0 && errno == ESRCH; }

std::pair<int, std::string> run(std::vector<std::string> argv, const std::string& url, double timeout_s = 10.0) {
  argv.insert(argv.end(), {"--lcm-url", url});
  ChildProcess p(argv);
  const int rc = p.wait(timeout_s);
  return {rc, p.output()};
}

void expect_three_running(const std::string& url) {
  auto [rc, out] = run({bin("cmctl"), "list"}, url);
  ASSERT_EQ(rc, 0) << out;
  // The hardware the manager follows, measured: sim_server in real time at the URDF's 1 kHz.
  EXPECT_TRUE(std::regex_search(out, std::regex("\nhardware: session [0-9a-f]+, real time, 1000 Hz( \\([0-9.]+ "
                                                "measured\\))?, step [0-9]+, last state 0\\.[0-9]+ s ago\n$")))
      << out;
  for (const std::string name : {"joint_state_controller ", "j1_controller ", "j2_controller "}) {
    const auto at = out.find(name);
    ASSERT_NE(at, std::string::npos) << out;
    EXPECT_NE(out.substr(at, out.find('\n', at) - at).find(" running "), std::string::npos) << out;
  }
}

// Ctrl-C: exit 0 within the 5 s budget, every child gone.
void stop_and_check(ChildProcess& launch, const std::map<std::string, pid_t>& pids) {
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(launch.stop(8.0, SIGINT), 0) << launch.output();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5.5);
  for (const auto& [name, pid] : pids) EXPECT_TRUE(gone(pid)) << name << " (pid " << pid << ") is still there";
}

}  // namespace

TEST(Launch, TurretBotUpAndDownCleanly) {
  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), source("config/turret_bot.launch.yaml"), "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  const auto pids = started_pids(launch.output());
  ASSERT_EQ(pids.size(), 4u) << launch.output();
  for (const std::string name : {"sim_server", "controller_manager", "state_publisher", "spawner"})
    EXPECT_TRUE(pids.count(name)) << name;
  expect_three_running(url);
  lcm::LCM lc(url);
  Recorder<link_poses_t> poses(lc, "link_poses");
  EXPECT_TRUE(pump_until(lc, [&] { return !poses.messages.empty(); }, 3.0));

  stop_and_check(launch, pids);
  const std::string out = launch.output();
  // Controllers first (the spawner unloads), then the servers.
  const auto unloaded = out.find("[spawner] unloaded joint_state_controller");
  const auto cm_down = out.find("[controller_manager] info: shutting down");
  ASSERT_NE(unloaded, std::string::npos) << out;
  ASSERT_NE(cm_down, std::string::npos) << out;
  EXPECT_LT(unloaded, cm_down);
  EXPECT_NE(out.find("[launch] all 4 processes stopped"), std::string::npos) << out;
  EXPECT_EQ(out.find(", cpu "), std::string::npos) << "real time: not pinned by default\n" << out;
}

// --rt-priority: both loop processes at SCHED_FIFO with memory locked, each spinning before its real-time deadline,
// and the robot runs; where SCHED_FIFO is not permitted, launch stops with the child's reason and what to do.
TEST(Launch, RtPriorityRunsBothLoopsAtSchedFifoSpinningAndTheFilesOwnFlagsWin) {
  auto [rc, dry] = run({bin("launch"), source("config/turret_bot.launch.yaml"), "--rt-priority", "20", "--dry-run"},
                       unique_lcm_url());
  ASSERT_EQ(rc, 0) << dry;
  const std::string lines = "\n" + dry;
  for (const std::string name : {"sim_server: ", "controller_manager: "}) {
    const auto at = lines.find("\n" + name) + 1;
    ASSERT_NE(at, 0u) << dry;
    const std::string line = lines.substr(at, lines.find('\n', at) - at);
    EXPECT_NE(line.find(" --rt-priority 20 --spin-us 150"), std::string::npos) << line;
  }
  std::tie(rc, dry) = run({bin("launch"), source("config/turret_bot.launch.yaml"), "--rt-priority", "20", "--mode",
                           "lockstep", "--dry-run"},
                          unique_lcm_url());
  EXPECT_EQ(dry.find("--spin-us"), std::string::npos) << "no spinning in lockstep\n" << dry;
  const std::string dir = temp_dir("launch_rt_own");
  const std::string file = dir + "/own.launch.yaml";
  std::ofstream(file) << "urdf: " << source("config/turret_bot.urdf") << "\nconfig: " << source("config/turret_bot.yaml")
                      << "\nrt_priority: 20\ncontroller_manager_args: [--spin-us=40]\n";
  std::tie(rc, dry) = run({bin("launch"), file, "--dry-run"}, unique_lcm_url());
  EXPECT_NE(dry.find("--rt-priority 20 --spin-us 150\n"), std::string::npos) << dry;
  EXPECT_NE(dry.find("--spin-us=40 --rt-priority 20\n"), std::string::npos) << dry;

  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), source("config/turret_bot.launch.yaml"), "--rt-priority", "20", "--lcm-url", url});
  if (!launch.wait_for_output("[launch] up:", 25.0)) {
    const std::string out = launch.output();
    ASSERT_NE(out.find("--rt-priority 20: SCHED_FIFO not permitted"), std::string::npos) << out;
    EXPECT_NE(launch.wait(10.0), 0) << out;
    GTEST_SKIP() << "SCHED_FIFO is not permitted here; launch said so and stopped";
  }
  const auto pids = started_pids(launch.output());
  for (const std::string name : {"sim_server", "controller_manager"}) {
    ASSERT_TRUE(pids.count(name)) << launch.output();
    EXPECT_EQ(sched_getscheduler(pids.at(name)), SCHED_FIFO) << name;
    sched_param p{};
    ASSERT_EQ(sched_getparam(pids.at(name), &p), 0);
    EXPECT_EQ(p.sched_priority, 20) << name;
  }
  const std::string out = launch.output();
  EXPECT_NE(out.find("spinning 150 us before each deadline"), std::string::npos) << out;
  EXPECT_NE(out.find("spinning 150 us around each real-time state"), std::string::npos) << out;
  expect_three_running(url);
  stop_and_check(launch, pids);
}

// A second launch onto a bus where a robot already runs in the same namespace would fight it for the robot.
TEST(Launch, RefusesANamespaceWhereAControllerManagerOrSimulatorRuns) {
  const std::string url = unique_lcm_url();
  const std::string urdf = source("config/turret_bot.urdf"), yaml = source("config/turret_bot.yaml");
  {
    ChildProcess cm({bin("controller_manager"), "--urdf", urdf, "--config", yaml, "--lcm-url", url});
    ASSERT_TRUE(cm.wait_for_output("ready (", 10.0)) << cm.output();
    auto [rc, out] = run({bin("launch"), source("config/turret_bot.launch.yaml")}, url);
    EXPECT_EQ(rc, 1) << out;
    EXPECT_NE(out.find("launch: error: a controller manager already answers on 'controller_manager/response' in the "
                       "default namespace (0 controller(s) loaded): a second one would fight it for the robot"),
              std::string::npos)
        << out;
    EXPECT_EQ(out.find("[launch] started"), std::string::npos) << "nothing started\n" << out;
    // Another namespace is another robot: that one comes up.
    ChildProcess other({bin("launch"), source("config/turret_bot.launch.yaml"), "--namespace", "r2", "--lcm-url", url});
    EXPECT_TRUE(other.wait_for_output("[launch] up:", 25.0)) << other.output();
    EXPECT_EQ(other.stop(15.0), 0) << other.output();
  }
  ChildProcess sim({bin("sim_server"), "--urdf", urdf, "--config", yaml, "--lcm-url", url});
  ASSERT_TRUE(sim.wait_for_output("ready (", 10.0)) << sim.output();
  auto [rc, out] = run({bin("launch"), source("config/turret_bot.launch.yaml")}, url);
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("launch: error: hardware already publishes 'hardware/state' in the default namespace"),
            std::string::npos)
      << out;
}

TEST(Launch, AChildsDeathStopsEverythingWithANonZeroExit) {
  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), source("config/turret_bot.launch.yaml"), "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  const auto pids = started_pids(launch.output());
  ASSERT_TRUE(pids.count("sim_server"));
  kill(pids.at("sim_server"), SIGKILL);
  EXPECT_EQ(launch.wait(8.0), 1) << launch.output();
  EXPECT_NE(launch.output().find("[launch] stopping (sim_server died of signal 9"), std::string::npos)
      << launch.output();
  EXPECT_NE(launch.output().find("launch: error: sim_server died of signal 9"), std::string::npos) << launch.output();
  for (const auto& [name, pid] : pids) EXPECT_TRUE(gone(pid)) << name;
}

TEST(Launch, FailedSpawnStopsEverythingAndSaysWhy) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("launch_fail");
  std::ofstream(dir + "/bad.launch.yaml") << "urdf: " << source("config/turret_bot.urdf") << "\nconfig: "
                                          << source("config/turret_bot.yaml")
                                          << "\ncontrollers: [j3_controller]\n";
  ChildProcess launch({bin("launch"), dir + "/bad.launch.yaml", "--lcm-url", url});
  EXPECT_EQ(launch.wait(25.0), 1) << launch.output();
  const std::string out = launch.output();
  EXPECT_NE(out.find("[spawner] error: controller 'j3_controller' failed to load"), std::string::npos) << out;
  EXPECT_NE(out.find("launch: error: spawner exited with code 1"), std::string::npos) << out;
  for (const auto& [name, pid] : started_pids(out)) EXPECT_TRUE(gone(pid)) << name;
}

TEST(Launch, ExtraProcessesRunWithTheRestAndAFailedOneIsReported) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("launch_extra");
  std::ofstream(dir + "/extra.launch.yaml")
      << "urdf: " << source("config/turret_bot.urdf") << "\nconfig: " << source("config/turret_bot.yaml")
      << "\nmode: lockstep\ncontrollers: [joint_state_controller]\nprocesses:\n"
      << "  - name: logger\n    command: [state-logger, joint_states, --output, " << dir << "/js.csv]\n"
      << "  - name: bad_cmd\n    command: [turret-cmd, j2_controller, 'sin(']\n";
  ChildProcess launch({bin("launch"), dir + "/extra.launch.yaml", "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  ASSERT_TRUE(launch.wait_for_output("[launch] bad_cmd exited with code 1", 5.0)) << launch.output();
  EXPECT_TRUE(launch.running()) << "an optional process's exit must not stop the rest";
  const auto pids = started_pids(launch.output());
  EXPECT_EQ(pids.size(), 5u) << launch.output();  // sim, manager, logger, bad_cmd, spawner
  EXPECT_TRUE(launch.wait_for_output("[logger] logging joint_states -> " + dir + "/js.csv", 5.0)) << launch.output();
  EXPECT_NE(launch.output().find("[bad_cmd] error: expression 'sin('"), std::string::npos) << launch.output();
  lcm::LCM lc(url);
  Recorder<joint_state_t> js(lc, "joint_states");
  ASSERT_TRUE(pump_until(lc, [&] { return js.messages.size() >= 5; }, 5.0));
  EXPECT_EQ(launch.stop(8.0, SIGINT), 1) << launch.output();
  EXPECT_NE(launch.output().find("launch: error: bad_cmd exited with code 1"), std::string::npos) << launch.output();
  for (const auto& [name, pid] : pids) EXPECT_TRUE(gone(pid)) << name;
  const Csv csv = read_csv(dir + "/js.csv");
  EXPECT_EQ(csv.header.size(), 9u);  // utime, 3 x 2 joints, name[0], name[1]
  EXPECT_GE(csv.rows.size(), 5u);
}

TEST(Launch, TheTutorialsRosLaunchFileWithOnlyThePackagePath) {
  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), source("test/tools/data/turret_bot/launch/gazebo_ros_control.launch"),
                       "--package-path", source("test/tools/data"), "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  const auto pids = started_pids(launch.output());
  for (const std::string name : {"sim_server", "controller_manager", "robot_state_publisher", "controller_spawner"})
    EXPECT_TRUE(pids.count(name)) << name << "\n" << launch.output();
  expect_three_running(url);
  lcm::LCM lc(url);
  Recorder<link_poses_t> poses(lc, "link_poses");
  EXPECT_TRUE(pump_until(lc, [&] { return !poses.messages.empty(); }, 3.0));
  stop_and_check(launch, pids);
}

namespace {

struct Trace {
  std::vector<double> t, q;
  std::string summary() const {
    if (t.empty()) return "no samples";
    return "samples " + std::to_string(t.size()) + ", t " + std::to_string(t.front()) + ".." + std::to_string(t.back()) +
           " s, q " + std::to_string(q.front()) + ".." + std::to_string(q.back());
  }
};

// Rise time of a step from `from` to `to`: 10 % to 90 % of the way.
double rise_time(const Trace& tr, double from, double to) {
  double t10 = -1, t90 = -1;
  for (size_t k = 0; k < tr.q.size(); ++k) {
    const double frac = (tr.q[k] - from) / (to - from);
    if (t10 < 0 && frac >= 0.1) t10 = tr.t[k];
    if (t90 < 0 && frac >= 0.9) t90 = tr.t[k];
  }
  return t10 >= 0 && t90 >= 0 ? t90 - t10 : 1e9;
}

// Sends j2 from `from` to `to` and records j2's position until `seconds` of
// sim time after it got 10 % of the way (bounded in wall time).
Trace step_j2(lcm::LCM& lc, const std::string& url, double from, double to, double seconds) {
  Recorder<joint_state_t> js(lc, "joint_states");
  auto [rc, out] = run({bin("turret-cmd"), "j2_controller", std::to_string(to)}, url);
  EXPECT_EQ(rc, 0) << out;
  Trace tr;
  size_t used = 0;
  double t10 = -1;
  pump_until(
      lc,
      [&] {
        for (; used < js.messages.size(); ++used) {
          const auto& m = js.messages[used];
          for (int k = 0; k < m.num_joints; ++k)
            if (m.name[k] == "j2") {
              tr.t.push_back(double(m.utime) * 1e-6);
              tr.q.push_back(m.position[k]);
              if (t10 < 0 && (m.position[k] - from) / (to - from) >= 0.1) t10 = tr.t.back();
            }
        }
        return t10 >= 0 && tr.t.back() - t10 >= seconds;
      },
      seconds + 8.0);
  return tr;
}

}  // namespace

TEST(Tune, ChangesTheSimGainsAndTheStepResponse) {
  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), source("config/turret_bot.launch.yaml"), "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  lcm::LCM lc(url);

  auto [rc, out] = run({bin("tune"), "j2"}, url);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_EQ(out, "j2 (sim_server): p 1  i 0  d 0.3  i_clamp [0, 0]  antiwindup false\n");
  // The tutorial's gains: a slow step (rotor inertia about j2 ~ 0.058 kg m^2).
  const Trace slow = step_j2(lc, url, 0.0, 1.0, 2.0);
  ASSERT_FALSE(slow.q.empty());
  EXPECT_NEAR(slow.q.back(), 1.0, 0.05) << slow.summary();

  std::tie(rc, out) = run({bin("tune"), "j2", "--p", "20", "--d", "1"}, url);
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("j2 (sim_server): p 20  i 0  d 1  "), std::string::npos) << out;
  std::tie(rc, out) = run({bin("tune"), "j2"}, url);
  EXPECT_EQ(out, "j2 (sim_server): p 20  i 0  d 1  i_clamp [0, 0]  antiwindup false\n");
  const Trace fast = step_j2(lc, url, 1.0, 0.0, 1.5);
  ASSERT_FALSE(fast.q.empty());
  EXPECT_NEAR(fast.q.back(), 0.0, 0.05) << fast.summary();

  const double slow_rise = rise_time(slow, 0.0, 1.0), fast_rise = rise_time(fast, 1.0, 0.0);
  std::printf("j2 rise time 10-90%%: %.3f s with p 1 d 0.3, %.3f s with p 20 d 1\n", slow_rise, fast_rise);
  EXPECT_LT(slow_rise, 5.0) << slow.summary();
  EXPECT_LT(fast_rise, 0.5 * slow_rise) << fast.summary();

  std::tie(rc, out) = run({bin("tune"), "j9"}, url);
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("tune: error: sim_server refused the query for 'j9'"), std::string::npos) << out;
  launch.stop(8.0);
}

// Under lockstep, turret-cmd --sim-time has the controller manager generate
// the commands (a command source): message i is delivered before the update
// of the i-th step after it registers, so every step gets its own command.
TEST(TurretCmd, SimTimeUnderLockstepGivesEveryStepItsOwnCommand) {
  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), source("config/turret_bot.launch.yaml"), "--mode", "lockstep", "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  // Lockstep: launch puts sim_server and controller_manager on one CPU (its `cpu: auto`).
  const std::regex on_cpu(R"(\[(sim_server|controller_manager)\] info: ready \(.*, cpu (\d+)\))");
  std::map<std::string, std::string> cpu_of;
  const std::string up = launch.output();
  for (std::sregex_iterator m(up.begin(), up.end(), on_cpu), end; m != end; ++m) cpu_of[(*m)[1]] = (*m)[2];
  ASSERT_EQ(cpu_of.size(), 2u) << up;
  EXPECT_EQ(cpu_of["sim_server"], cpu_of["controller_manager"]) << up;
  lcm::LCM lc(url);
  Recorder<hardware_command_t> cmds(lc, "hardware/command");
  Recorder<float64_t> sent(lc, "j2_controller/command");
  ChildProcess cmd({bin("turret-cmd"), "j2_controller", "0.001*(i+1)", "--sim-time", "--count", "500", "--lcm-url",
                    url});
  ASSERT_EQ(cmd.wait(20.0), 0) << cmd.output();
  EXPECT_NE(cmd.output().find("ended (count reached) after 500 tick(s)"), std::string::npos) << cmd.output();
  pump_until(lc, [&] { return sent.messages.size() >= 500; }, 2.0);
  pump_until(lc, [] { return false; }, 0.2);
  ASSERT_EQ(sent.messages.size(), 500u);
  // Message i is published with the utime of the step it was due at (1 kHz control).
  for (size_t i = 1; i < sent.messages.size(); ++i)
    EXPECT_EQ(sent.messages[i].utime - sent.messages[0].utime, int64_t(i) * 1000) << i;
  std::map<int64_t, double> used;  // step -> j2's command
  for (const auto& c : cmds.messages)
    if (c.num_actuators >= 2 && c.mode[1] != hardware_command_t::MODE_NONE) used[c.step] = c.command[1];
  const int64_t first = sent.messages[0].utime / 1000;
  int exact = 0;
  for (int64_t i = 0; i < 500; ++i) {
    const auto it = used.find(first + i);
    if (it == used.end()) continue;  // this process's UDP socket missed it
    EXPECT_DOUBLE_EQ(it->second, 0.001 * double(i + 1)) << "step " << first + i;
    exact += it->second == 0.001 * double(i + 1);
  }
  std::printf("turret-cmd --sim-time under lockstep: %d of 500 steps seen, each with its own command\n", exact);
  EXPECT_GT(exact, 400);

  // Without --count or --duration it runs until Ctrl-C, which removes the source.
  ChildProcess forever({bin("turret-cmd"), "j2_controller", "0.25", "--sim-time", "--rate", "60", "--lcm-url", url});
  ASSERT_TRUE(forever.wait_for_output("tick 0 at the next cycle", 5.0)) << forever.output();
  const size_t before = sent.messages.size();
  ASSERT_TRUE(pump_until(lc, [&] { return sent.messages.size() > before + 3; }, 5.0));
  EXPECT_EQ(forever.stop(5.0, SIGINT), 0) << forever.output();
  EXPECT_NE(forever.output().find("command source for 'j2_controller' removed after"), std::string::npos)
      << forever.output();
  pump_until(lc, [] { return false; }, 0.3);
  const size_t after = sent.messages.size();
  pump_until(lc, [] { return false; }, 0.3);
  EXPECT_EQ(sent.messages.size(), after) << "commands after the source was removed";
  launch.stop(8.0);
}

// One of three controllers cannot load (a joint the URDF does not have): the robot comes up with the other two,
// launch's up line names the failed one, and launch exits non-zero when stopped.
TEST(Launch, AControllerThatFailsToLoadIsNamedAndTheRobotRunsWithTheOthers) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("launch_one_bad");
  std::ofstream(dir + "/c.yaml") << read_text(source("config/turret_bot.yaml"))
                                 << "bad_controller:\n  type: position_controllers/JointPositionController\n"
                                    "  joint: j9\n";
  std::ofstream(dir + "/bad.launch.yaml") << "urdf: " << source("config/turret_bot.urdf") << "\nconfig: c.yaml\n"
                                          << "controllers: [joint_state_controller, bad_controller, j1_controller]\n";
  ChildProcess launch({bin("launch"), dir + "/bad.launch.yaml", "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up:", 25.0)) << launch.output();
  EXPECT_NE(launch.output().find("[launch] up: controllers joint_state_controller, j1_controller; FAILED to spawn "
                                 "bad_controller"),
            std::string::npos)
      << launch.output();
  EXPECT_NE(launch.output().find("error: controller 'bad_controller' failed to load: "), std::string::npos)
      << launch.output();
  auto [rc, out] = run({bin("cmctl"), "list"}, url);
  const auto at = out.find("j1_controller ");
  ASSERT_NE(at, std::string::npos) << out;
  EXPECT_NE(out.substr(at, out.find('\n', at) - at).find(" running "), std::string::npos) << out;
  const auto pids = started_pids(launch.output());
  EXPECT_NE(launch.stop(8.0, SIGINT), 0) << launch.output();  // the failure shows in the exit status
  for (const auto& [name, pid] : pids) EXPECT_TRUE(gone(pid)) << name;
}

// A robot without a launch file (issue 32, item 5): --urdf and --config make the plan a launch file with urdf:,
// config: and controllers: makes, every configured controller by default; the model's warnings, read by sim_server and
// controller_manager alike, are printed once.
TEST(Launch, FromUrdfAndConfigWithoutAFileEveryControllerAndEachWarningOnce) {
  auto [rc, dry] = run({bin("launch"), "--urdf", source("config/turret_bot.urdf"), "--config",
                        source("config/turret_bot.yaml"), "--dry-run"},
                       unique_lcm_url());
  ASSERT_EQ(rc, 0) << dry;
  EXPECT_NE(("\n" + dry).find("\nspawner: spawner joint_state_controller j1_controller j2_controller"), std::string::npos)
      << dry;
  EXPECT_NE(("\n" + dry).find("\nsim_server: sim_server --urdf " + source("config/turret_bot.urdf") + " --config " +
                     source("config/turret_bot.yaml")),
            std::string::npos)
      << dry;
  std::tie(rc, dry) = run({bin("launch"), "--urdf", source("config/turret_bot.urdf"), "--config",
                           source("config/turret_bot.yaml"), "--controllers", "j1_controller", "--dry-run"},
                          unique_lcm_url());
  EXPECT_NE(("\n" + dry).find("\nspawner: spawner j1_controller"), std::string::npos) << dry;
  std::tie(rc, dry) = run({bin("launch"), source("config/turret_bot.launch.yaml"), "--urdf",
                           source("config/turret_bot.urdf"), "--dry-run"},
                          unique_lcm_url());
  EXPECT_EQ(rc, 2) << dry;
  EXPECT_NE(dry.find("launch: error: --urdf: give a launch FILE or --urdf (with --config), not both"),
            std::string::npos)
      << dry;
  std::tie(rc, dry) = run({bin("launch"), source("config/turret_bot.launch.yaml"), "--config",
                           source("config/turret_bot.yaml"), "--dry-run"},
                          unique_lcm_url());
  EXPECT_EQ(rc, 2) << dry;
  EXPECT_NE(dry.find("launch: error: --config: goes with --urdf; a launch FILE names its own config"),
            std::string::npos)
      << dry;
  std::tie(rc, dry) = run({bin("launch"), "--dry-run"}, unique_lcm_url());
  EXPECT_EQ(rc, 2) << dry;
  EXPECT_NE(dry.find("give a launch FILE, or the robot with --urdf R.urdf --config C.yaml"), std::string::npos) << dry;

  // j2 without its transmission: its pid_gains are a model warning both servers find.
  const std::string dir = temp_dir("launch_flags");
  std::string urdf = read_text(source("config/turret_bot.urdf"));
  const auto t2 = urdf.find("<transmission name=\"t2\">");
  ASSERT_NE(t2, std::string::npos);
  urdf.erase(t2, urdf.find("</transmission>", t2) + std::string("</transmission>").size() - t2);
  std::ofstream(dir + "/no_t2.urdf") << urdf;
  const std::string url = unique_lcm_url();
  ChildProcess launch({bin("launch"), "--urdf", dir + "/no_t2.urdf", "--config", source("config/turret_bot.yaml"),
                       "--controllers", "joint_state_controller,j1_controller", "--lcm-url", url});
  ASSERT_TRUE(launch.wait_for_output("[launch] up: controllers joint_state_controller, j1_controller", 25.0))
      << launch.output();
  const std::string out = launch.output();
  const std::string warning = "gazebo_ros_control/pid_gains/j2: joint has no transmission in " + dir + "/no_t2.urdf";
  const auto first = out.find(warning);
  EXPECT_NE(first, std::string::npos) << out;
  EXPECT_EQ(out.find(warning, first + 1), std::string::npos) << "printed twice\n" << out;
  EXPECT_EQ(launch.stop(8.0, SIGINT), 0) << launch.output();
}

// launch takes --arg as every program that reads the robot's files does, for $(arg NAME) in the YAML; files that do
// not load are named once, by launch, with exit 3 as the convention says, before any server starts and names them
// again (issue 32, items 4 and 5).
TEST(Launch, TakesArgAndNamesABadFileOnceWithExitThreeBeforeStartingAnything) {
  const std::string urdf = source("test/robots/multi_trans_arm.urdf"), yaml = source("test/robots/multi_trans_arm.yaml");
  auto [rc, dry] = run({bin("launch"), "--urdf", urdf, "--config", yaml, "--arg", "arm_id:=arm", "--dry-run"},
                       unique_lcm_url());
  ASSERT_EQ(rc, 0) << dry;
  EXPECT_NE(("\n" + dry).find("\nsim_server: sim_server --urdf " + urdf + " --config " + yaml + " --arg arm_id=arm"),
            std::string::npos)
      << dry;
  EXPECT_NE(("\n" + dry).find("\nspawner: spawner "), std::string::npos) << "the controllers, read with the arg\n" << dry;

  const std::string url = unique_lcm_url();
  ChildProcess missing({bin("launch"), "--urdf", urdf, "--config", yaml, "--lcm-url", url});
  EXPECT_EQ(missing.wait(25.0), 3) << missing.output();
  const std::string problem = "$(arg arm_id) has no value; give its value with --arg arm_id=VALUE";
  const size_t first = missing.output().find(problem);
  EXPECT_NE(first, std::string::npos) << missing.output();
  // Once: launch reads the files before it starts the servers, which would each name it again.
  EXPECT_EQ(missing.output().find(problem, first + 1), std::string::npos) << missing.output();
  EXPECT_EQ(missing.output().find("started sim_server"), std::string::npos) << missing.output();
  for (const auto& [name, pid] : started_pids(missing.output())) EXPECT_TRUE(gone(pid)) << name;

  const std::string dir = temp_dir("launch_bad_file");
  std::ofstream(dir + "/bad.urdf") << "<robot name=\"bad\"><link name=\"base\">\n";  // not well-formed
  std::ofstream(dir + "/bad.launch.yaml") << "urdf: " << dir << "/bad.urdf\nconfig: " << source("config/turret_bot.yaml")
                                          << "\ncontrollers: [j1_controller]\n";
  ChildProcess bad({bin("launch"), dir + "/bad.launch.yaml", "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(bad.wait(25.0), 3) << bad.output();
  EXPECT_NE(bad.output().find("launch: error: " + dir + "/bad.urdf:1: malformed XML"), std::string::npos)
      << bad.output();
  EXPECT_EQ(bad.output().find("started sim_server"), std::string::npos) << bad.output();
}
