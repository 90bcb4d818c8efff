// cmctl and spawner against a real controller_manager (no hardware: switches
// apply at once) on a private LCM URL per test.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <tuple>

#include "test/support/lcm_test.hpp"
#include "test/support/process.hpp"
#include "test/tools/tool_test_util.hpp"

using namespace lcm_control::testing;

namespace {

class CmTools : public ::testing::Test {
 protected:
  void SetUp() override { start_manager(source("config/turret_bot.yaml")); }
  void start_manager(const std::string& config) {
    cm_ = std::make_unique<ChildProcess>(std::vector<std::string>{
        bin("controller_manager"), "--urdf", source("config/turret_bot.urdf"), "--config", config, "--lcm-url", url_});
    ASSERT_TRUE(cm_->wait_for_output("ready (", 10.0)) << cm_->output();
  }
  // Runs a tool to completion; returns (exit code, output).
  std::pair<int, std::string> run(std::vector<std::string> argv, double timeout_s = 10.0) {
    argv.insert(argv.end(), {"--lcm-url", url_});
    ChildProcess p(argv);
    const int rc = p.wait(timeout_s);
    return {rc, p.output()};
  }
  std::string url_ = unique_lcm_url();
  std::unique_ptr<ChildProcess> cm_;
};

}  // namespace

TEST_F(CmTools, SpawnerStartsTheTutorialControllersAndCmctlListsThemRunning) {
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller", "--lcm-url", url_});
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();
  auto [rc, out] = run({bin("cmctl"), "list"});
  ASSERT_EQ(rc, 0) << out;
  const auto lines = split(out.substr(0, out.size() - 1), '\n');
  ASSERT_EQ(lines.size(), 5u) << out;  // header, three controllers, the hardware
  // No simulator in this fixture: the spawner succeeds, but says so, and so does the list.
  EXPECT_EQ(lines[4].rfind("hardware: no hardware state received on 'hardware/state': is sim_server (or the robot's "
                           "driver) running with this namespace and LCM URL?", 0),
            0u)
      << out;
  EXPECT_NE(spawner.output().find("spawner: warning: the controllers run, but the controller manager reports no "
                                  "hardware state received"),
            std::string::npos)
      << spawner.output();
  EXPECT_EQ(split(lines[0], ' ')[0], "NAME");
  EXPECT_NE(lines[0].find("TYPE"), std::string::npos);
  EXPECT_NE(lines[0].find("INTERFACE"), std::string::npos);
  for (const std::string name : {"joint_state_controller", "j1_controller", "j2_controller"}) {
    bool found = false;
    for (const auto& l : lines)
      if (l.rfind(name + " ", 0) == 0) {
        found = true;
        EXPECT_NE(l.find(" running "), std::string::npos) << l;
      }
    EXPECT_TRUE(found) << name << "\n" << out;
  }
  EXPECT_NE(out.find("position_controllers/JointPositionController  running  j2"), std::string::npos) << out;

  EXPECT_EQ(spawner.stop(5.0), 0) << spawner.output();
  EXPECT_NE(spawner.output().find("stopped and unloaded"), std::string::npos) << spawner.output();
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "no controllers loaded\n") << out;
}

// A switch made after the spawner started its controllers (one stopped by hand) does not spoil its Ctrl-C: it stops
// what still runs and unloads all it loaded.
TEST_F(CmTools, SpawnerStopsAndUnloadsCleanlyAfterTheUserSwitched) {
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "j1_controller", "j2_controller", "--lcm-url", url_});
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();
  auto [rc, out] = run({bin("cmctl"), "stop", "j2_controller"});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_EQ(spawner.stop(5.0), 0) << spawner.output();
  EXPECT_EQ(spawner.output().find("was refused"), std::string::npos) << spawner.output();
  EXPECT_NE(spawner.output().find("stopped and unloaded, bye"), std::string::npos) << spawner.output();
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "no controllers loaded\n") << out;
}

// One good and one bad controller spawned together (ROS's spawner: the bad one is reported, the others run).
TEST_F(CmTools, SpawnerNamesTheControllerThatFailsToLoadKeepsTheOthersAndExitsNonZero) {
  cm_->stop(5.0);
  const std::string dir = temp_dir("spawner_one_bad");
  std::ofstream(dir + "/c.yaml") << read_text(source("config/turret_bot.yaml"))
                                 << "bad_controller:\n  type: position_controllers/JointPositionController\n"
                                    "  joint: j9\n";
  start_manager(dir + "/c.yaml");
  ChildProcess spawner({bin("spawner"), "joint_state_controller", "bad_controller", "j1_controller", "--lcm-url", url_});
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();
  const std::string said = spawner.output();
  EXPECT_NE(said.find("spawner: error: controller 'bad_controller' failed to load: "), std::string::npos) << said;
  EXPECT_NE(said.find("'j9'"), std::string::npos) << said;
  EXPECT_NE(said.find("spawner: ready: joint_state_controller, j1_controller running; failed: bad_controller "
                      "(Ctrl-C"),
            std::string::npos)
      << said;
  auto [rc, out] = run({bin("cmctl"), "list"});
  EXPECT_NE(out.find("joint_state_controller "), std::string::npos) << out;
  EXPECT_NE(out.find("j1_controller "), std::string::npos) << out;
  EXPECT_EQ(out.find("bad_controller"), std::string::npos) << out;
  for (const auto& l : split(out, '\n')) {
    if (l.rfind("j1_controller ", 0) == 0) {
      EXPECT_NE(l.find(" running "), std::string::npos) << l;
    }
  }
  EXPECT_EQ(spawner.stop(5.0), 1) << spawner.output();  // the failure shows in the exit status at the end
  EXPECT_NE(spawner.output().find("stopped and unloaded"), std::string::npos) << spawner.output();
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "no controllers loaded\n") << out;
}

TEST_F(CmTools, SpawnerWhoseOnlyControllerFailsExitsNonZeroAtOnce) {
  auto [rc, out] = run({bin("spawner"), "j3_controller"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("spawner: error: controller 'j3_controller' failed to load: cannot load 'j3_controller': there "
                     "is no 'j3_controller' entry"),
            std::string::npos)
      << out;
}

TEST_F(CmTools, SpawnerActivateAsGroupIsAllOrNothing) {
  auto [rc, out] = run({bin("spawner"), "joint_state_controller", "j3_controller", "--activate-as-group"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("spawner: error: controller 'j3_controller' failed to load: cannot load 'j3_controller': there "
                     "is no 'j3_controller' entry"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("--activate-as-group: none spawned"), std::string::npos) << out;
  EXPECT_NE(out.find("unloaded joint_state_controller"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "no controllers loaded\n") << out;
}

TEST_F(CmTools, SpawnerConflictStartsTheFirstAndNamesTheOther) {
  cm_->stop(5.0);
  const std::string dir = temp_dir("spawner_conflict");
  std::ofstream(dir + "/c.yaml") << read_text(source("config/turret_bot.yaml"))
                                 << "j1_other:\n  type: position_controllers/JointPositionController\n  joint: j1\n";
  start_manager(dir + "/c.yaml");
  {
    ChildProcess spawner({bin("spawner"), "j1_controller", "j1_other", "--lcm-url", url_});
    ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();
    const std::string said = spawner.output();
    EXPECT_NE(said.find("starting [j1_controller, j1_other] together was refused"), std::string::npos) << said;
    EXPECT_NE(said.find("spawner: error: controller 'j1_other' could not start: "), std::string::npos) << said;
    EXPECT_NE(said.find("spawner: ready: j1_controller running; failed: j1_other"), std::string::npos) << said;
    EXPECT_EQ(spawner.stop(5.0), 1) << spawner.output();
  }
  auto [rc, out] = run({bin("spawner"), "j1_controller", "j1_other", "--activate-as-group"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("spawner: error: could not start [j1_controller, j1_other] (--activate-as-group: one strict "
                     "switch, so none started): "),
            std::string::npos)
      << out;
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_EQ(out.substr(0, out.find('\n') + 1), "no controllers loaded\n") << out;
}

TEST_F(CmTools, SpawnerExitsPromptlyWhenTheManagerIsGone) {
  ChildProcess spawner({bin("spawner"), "j1_controller", "--lcm-url", url_});
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();
  EXPECT_EQ(cm_->stop(5.0), 0);
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(spawner.stop(5.0), 0) << spawner.output();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 3.0);
  EXPECT_NE(spawner.output().find("gave up stopping and unloading [j1_controller]"), std::string::npos)
      << spawner.output();
}

TEST_F(CmTools, CmctlLoadStartSwitchStopUnloadReload) {
  auto [rc, out] = run({bin("cmctl"), "load", "j1_controller", "j2_controller"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("cmctl"), "start", "j1_controller"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_NE(out.find("j1_controller  position_controllers/JointPositionController  running"), std::string::npos)
      << out;
  std::tie(rc, out) = run({bin("cmctl"), "switch", "--stop", "j1_controller", "--start", "j2_controller"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_NE(out.find("j2_controller  position_controllers/JointPositionController  running"), std::string::npos)
      << out;
  EXPECT_EQ(out.find("j1_controller  position_controllers/JointPositionController  running"), std::string::npos)
      << out;
  std::tie(rc, out) = run({bin("cmctl"), "stop", "j2_controller"});
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("cmctl"), "unload", "j1_controller", "j2_controller"});
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list-types"});
  EXPECT_NE(out.find("position_controllers/JointPositionController\n"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "reload", "--force"});
  EXPECT_EQ(rc, 0) << out;
}

TEST_F(CmTools, CmctlRefusalAndSilence) {
  auto [rc, out] = run({bin("cmctl"), "start", "j1_controller"});
  EXPECT_EQ(rc, 1) << out;
  EXPECT_NE(out.find("cmctl: error: "), std::string::npos) << out;
  EXPECT_NE(out.find("j1_controller"), std::string::npos) << out;

  ChildProcess lonely({bin("cmctl"), "list", "--timeout", "0.5", "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(lonely.wait(5.0), 4);
  EXPECT_NE(lonely.output().find("cmctl: error: no answer from the controller manager within 0.5 s to list (sent on "
                                 "'controller_manager/request', nothing came back on 'controller_manager/response')"),
            std::string::npos)
      << lonely.output();
}

TEST_F(CmTools, TurretCmdSaysWhenNothingTakesItsCommands) {
  auto [rc, out] = run({bin("turret-cmd"), "j1_controller", "0.5"});
  EXPECT_EQ(rc, 0) << out;  // sent anyway, as rostopic pub does
  EXPECT_NE(out.find("turret-cmd: warning: 'j1_controller' is not loaded in the controller manager (loaded: none): "
                     "nothing takes the commands on 'j1_controller/command' until `spawner j1_controller` starts it"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("turret-cmd: warning: the controller manager reports no hardware state received"),
            std::string::npos)
      << out;
  std::tie(rc, out) = run({bin("cmctl"), "load", "j1_controller"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("turret-cmd"), "/j1_controller/command", "0.5"});  // the ROS-style channel too
  EXPECT_NE(out.find("turret-cmd: warning: 'j1_controller' is initialized, not running: it ignores the commands on "
                     "'j1_controller/command' until `cmctl start j1_controller`"),
            std::string::npos)
      << out;
  std::tie(rc, out) = run({bin("turret-cmd"), "some/other/channel", "0.5"});
  EXPECT_EQ(out.find("warning"), std::string::npos) << "not a controller's channel: nothing to check\n" << out;

  ChildProcess lonely({bin("turret-cmd"), "j1_controller", "0.5", "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(lonely.wait(5.0), 0) << lonely.output();
  EXPECT_NE(lonely.output().find("turret-cmd: warning: no controller manager answers on 'controller_manager/response': "
                                 "nothing takes the commands on 'j1_controller/command' until one runs"),
            std::string::npos)
      << lonely.output();
}

// LCM_CONTROL_NAMESPACE is every tool's --namespace unless the flag is given; a tool that hears its robot only under
// another namespace says which at once, not after its whole --timeout (issue 32, item 2).
TEST(Namespaces, TheEnvironmentGivesTheDefaultAndAnotherNamespaceIsNamedAtOnce) {
  const std::string url = unique_lcm_url();
  ChildProcess cm({bin("controller_manager"), "--urdf", source("config/turret_bot.urdf"), "--config",
                   source("config/turret_bot.yaml"), "--lcm-url", url, "--namespace", "rrbot"});
  ASSERT_TRUE(cm.wait_for_output("ready (", 10.0)) << cm.output();
  auto run_with = [&](std::vector<std::string> argv, std::map<std::string, std::string> env) {
    argv.insert(argv.end(), {"--lcm-url", url});
    ChildProcess p(argv, env);
    const int rc = p.wait(20.0);
    return std::make_pair(rc, p.output());
  };
  auto [rc, out] = run_with({bin("cmctl"), "list"}, {{"LCM_CONTROL_NAMESPACE", "rrbot"}});
  EXPECT_EQ(rc, 0) << out;
  EXPECT_EQ(out.rfind("no controllers loaded\nhardware: no hardware state received on 'rrbot/hardware/state'", 0), 0u)
      << out;
  std::tie(rc, out) = run_with({bin("cmctl"), "list", "--namespace", "rrbot"}, {{"LCM_CONTROL_NAMESPACE", "other"}});
  EXPECT_EQ(rc, 0) << "the flag wins\n" << out;

  // The manager publishes its statistics once a second: heard under rrbot/ within that, well before --timeout 15.
  std::tie(rc, out) = run_with({bin("cmctl"), "list", "--timeout", "15"}, {{"LCM_CONTROL_NAMESPACE", ""}});
  EXPECT_EQ(rc, 4) << out;
  EXPECT_NE(out.find("cmctl: error: no answer from the controller manager within "), std::string::npos) << out;
  EXPECT_NE(out.find("; 'rrbot/controller_manager/statistics' is heard under namespace 'rrbot': did you mean "
                     "--namespace rrbot?\n"),
            std::string::npos)
      << out;
  EXPECT_EQ(out.find("within 15 s"), std::string::npos) << "named at once, not after the timeout\n" << out;
  std::tie(rc, out) = run_with({bin("turret-cmd"), "j1_controller", "0.5"}, {{"LCM_CONTROL_NAMESPACE", "r2"}});
  EXPECT_EQ(rc, 0) << out;  // sent anyway, as rostopic pub does
  EXPECT_NE(out.find("turret-cmd: warning: no controller manager answers on 'r2/controller_manager/response'"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("turret-cmd: sent 1 message on 'r2/j1_controller/command'"), std::string::npos) << out;
}

// One validation: what doctor refuses, controller_manager refuses with the same words (issue 12: `jont: j2` and
// `publish_rat` passed doctor and were refused by the manager).
TEST(DoctorAndManager, RefuseTheSameControllersWithTheSameReason) {
  const std::string dir = temp_dir("doctor_cm");
  std::string yaml = read_text(source("config/turret_bot.yaml"));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"  joint: j2", "  jont: j2"},
                                 {"publish_rate: 60", "publish_rat: 60"}})
    yaml.replace(yaml.find(from), from.size(), to);
  std::ofstream(dir + "/typo.yaml") << yaml;
  const std::string urdf = source("config/turret_bot.urdf");
  ChildProcess doctor({bin("doctor"), "--urdf", urdf, "--config", dir + "/typo.yaml"});
  EXPECT_EQ(doctor.wait(10.0), 3) << doctor.output();
  const std::string url = unique_lcm_url();
  ChildProcess cm({bin("controller_manager"), "--urdf", urdf, "--config", dir + "/typo.yaml", "--lcm-url", url});
  ASSERT_TRUE(cm.wait_for_output("ready (", 10.0)) << cm.output();
  for (const std::string controller : {"j2_controller", "joint_state_controller"}) {
    const std::string why = dir + "/typo.yaml: " + controller +
                            (controller == "j2_controller" ? "/joint: missing (required)" : "/publish_rate: missing (required)");
    EXPECT_NE(doctor.output().find("doctor: error: " + why), std::string::npos) << doctor.output();
    ChildProcess load({bin("cmctl"), "load", controller, "--lcm-url", url});
    EXPECT_EQ(load.wait(10.0), 1) << load.output();
    EXPECT_NE(load.output().find(why), std::string::npos) << load.output();
  }
}

TEST(Spawner, WithoutAManagerGivesUpWithinTheTimeout) {
  ChildProcess p({bin("spawner"), "j1_controller", "--timeout", "1", "--lcm-url", unique_lcm_url()});
  EXPECT_EQ(p.wait(5.0), 4) << p.output();
  EXPECT_NE(p.output().find("waiting up to 1 s for the controller manager on 'controller_manager/request'"),
            std::string::npos)
      << p.output();
  EXPECT_NE(p.output().find("spawner: error: no answer from the controller manager within 1 s"), std::string::npos)
      << p.output();
}

// A controller with its own PID answers tune on <controller>/gains (dynamic
// reconfigure of effort_controllers/JointPositionController).
TEST(Tune, AControllersOwnPid) {
  const std::string url = unique_lcm_url();
  const std::string dir = temp_dir("tune_controller");
  std::string urdf = read_text(source("config/turret_bot.urdf"));
  for (size_t p; (p = urdf.find("PositionJointInterface")) != std::string::npos;)
    urdf.replace(p, 22, "EffortJointInterface");
  std::ofstream(dir + "/effort.urdf") << urdf;
  std::ofstream(dir + "/effort.yaml") << "j2_controller:\n  type: effort_controllers/JointPositionController\n"
                                         "  joint: j2\n  pid: {p: 10.0, i: 0.5, d: 1.0, i_clamp: 2.0}\n";
  ChildProcess cm({bin("controller_manager"), "--urdf", dir + "/effort.urdf", "--config", dir + "/effort.yaml",
                   "--lcm-url", url});
  ASSERT_TRUE(cm.wait_for_output("ready (", 10.0)) << cm.output();
  auto run = [&](std::vector<std::string> argv) {
    argv.insert(argv.end(), {"--lcm-url", url});
    ChildProcess p(argv);
    const int rc = p.wait(10.0);
    return std::make_pair(rc, p.output());
  };
  auto [rc, out] = run({bin("tune"), "j2", "--owner", "j2_controller", "--timeout", "0.5"});
  EXPECT_EQ(rc, 4) << out;
  EXPECT_NE(out.find("no answer from 'j2_controller' within 0.5 s"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "load", "j2_controller"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("tune"), "j2", "--owner", "j2_controller"});
  EXPECT_EQ(out, "j2 (j2_controller): p 10  i 0.5  d 1  i_clamp [-2, 2]  antiwindup false\n");
  std::tie(rc, out) = run({bin("tune"), "j2", "--owner", "j2_controller", "--p", "20", "--i-clamp", "3",
                           "--antiwindup", "true"});
  EXPECT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("tune"), "j2", "--owner", "j2_controller"});
  EXPECT_EQ(out, "j2 (j2_controller): p 20  i 0.5  d 1  i_clamp [-3, 3]  antiwindup true\n");
}

// ROS 2's `ros2 control` verbs on a robot from ROS 2 files: states named inactive / active, each joint's interfaces
// with who claims them, and the spawner's ROS 2 flags.
TEST_F(CmTools, Ros2VerbsNameStatesAsRos2AndListTheHardwareInterfaces) {
  cm_->stop(5);
  cm_ = std::make_unique<ChildProcess>(std::vector<std::string>{
      bin("controller_manager"), "--urdf", source("test/controller_manager/data/ros2_bot.urdf"), "--config",
      source("test/controller_manager/data/ros2_bot.yaml"), "--lcm-url", url_});
  ASSERT_TRUE(cm_->wait_for_output("ready (", 10.0)) << cm_->output();
  auto [rc, out] = run({bin("cmctl"), "load-controller", "elbow_forward", "--set-state", "active"});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("elbow_forward is active"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "set-controller-state", "elbow_trajectory", "inactive"});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("elbow_trajectory is inactive"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list-controllers"});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("forward_command_controller/ForwardCommandController    active"), std::string::npos) << out;
  EXPECT_NE(out.find("joint_trajectory_controller/JointTrajectoryController  inactive"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list-hardware-interfaces"});
  ASSERT_EQ(rc, 0) << out;
  EXPECT_NE(out.find("command interfaces\n\tlift/position [available] [unclaimed]\n"
                     "\telbow/velocity [available] [claimed by elbow_forward]\n"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("state interfaces\n\tlift/position\n\tlift/velocity\n"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("cmctl"), "switch-controllers", "--activate", "elbow_trajectory", "--deactivate",
                           "elbow_forward", "--strict"});
  ASSERT_EQ(rc, 0) << out;
  std::tie(rc, out) = run({bin("cmctl"), "list-hardware-interfaces"});
  EXPECT_NE(out.find("elbow/velocity [available] [claimed by elbow_trajectory]"), std::string::npos) << out;

  ChildProcess spawner({bin("spawner"), "base", "--inactive", "-c", "/controller_manager", "--lcm-url", url_});
  ASSERT_TRUE(spawner.wait_for_output("spawner: ready", 10.0)) << spawner.output();
  std::tie(rc, out) = run({bin("cmctl"), "list"});
  EXPECT_NE(out.find("diff_drive_controller/DiffDriveController              inactive"), std::string::npos) << out;
  std::tie(rc, out) = run({bin("spawner"), "base", "-c", "/other/arm_manager"});
  EXPECT_NE(rc, 0);
  EXPECT_NE(out.find("--controller-manager /other/arm_manager: the node here is always 'controller_manager'"),
            std::string::npos)
      << out;
}
