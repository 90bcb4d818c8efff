// The scenario program end to end (tools/lib/scenarios): a deliberately broken controller fails the right checks
// with their values, a folder runs one scenario per CPU into a table and JUnit XML (passed, failed, skipped, a file
// that cannot run, one that overruns its time), a golden log replays bit for bit until a gain changes, and an input
// the controller manager refuses fails where it is written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "test/support/process.hpp"

namespace lt = lcm_control::testing;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("scenario_test_" + name + "_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// turret_bot holding j1 at 0.5 (config: the YAML to use), checked at the end.
std::string turret(const std::string& config, double duration = 2, const std::string& extra = "") {
  return "urdf: " + lt::source("config/turret_bot.urdf") + "\nconfig: " + config +
         "\ncontrollers: [joint_state_controller, j1_controller, j2_controller]\nduration: " + std::to_string(duration) +
         "\ntimeline:\n  - {at: 0.1, command: {controller: j1_controller, value: 0.5}}\n"
         "  - {at: 0.1, command: {controller: j2_controller, value: 1.0}}\n" + extra +
         "checks:\n  - {field: \"position[j1]\", at: 2, near: 0.5, tolerance: 0.02}\n"
         "  - {field: \"position[j2]\", at: 2, near: 1.0, tolerance: 0.05}\n";
}

void write(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

}  // namespace

TEST(ScenarioRunner, ABrokenControllerFailsTheRightChecksWithTheirValues) {
  const fs::path dir = scratch("broken");
  lt::ChildProcess run({lt::bin("scenario"), "run", lt::source("test/e2e/data/broken_effort_gains.scenario.yaml"),
                        "--junit", (dir / "out.xml").string()});
  ASSERT_EQ(run.wait(60), 1) << run.output();
  const std::string out = run.output();
  EXPECT_NE(out.find("broken_effort_gains  FAILED"), std::string::npos) << out;
  // The goal's result, and the two joints the weak gains leave short, each with the value it saw; the checks that
  // still hold (joint1 and joint3 reach their goals; the arm is still at rest) pass.
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(FAIL goal of arm_controller SUCCEEDED by t=3.5 s \(.*:16: check\): goal 1000 GOAL_TOLERANCE_VIOLATED at t=3.500 s: goal tolerance violated on joint 'joint2')")))
      << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(FAIL joint_states position\[joint2\] at t=5 s \(.*\): position\[joint2\] = 0\.4[0-9]+ at t=5\.000 s, wanted 0\.3 ± 0\.01)")))
      << out;
  EXPECT_NE(out.find("FAIL joint_states position[joint4] at t=5 s"), std::string::npos) << out;
  EXPECT_EQ(out.find("FAIL joint_states position[joint1]"), std::string::npos) << out;
  EXPECT_NE(out.find("1 scenario(s): 0 passed, 1 failed, 0 error(s), 0 skipped"), std::string::npos) << out;
  const std::string xml = read(dir / "out.xml");
  EXPECT_NE(xml.find(R"(<testsuite name="scenarios" tests="1" failures="1" errors="0" skipped="0")"), std::string::npos) << xml;
  EXPECT_EQ(std::count(xml.begin(), xml.end(), '\n') > 5, true);
  EXPECT_NE(xml.find("<failure message=\"goal of arm_controller SUCCEEDED by t=3.5 s: goal 1000 GOAL_TOLERANCE_VIOLATED"),
            std::string::npos) << xml;
  // The same arm and goal under the gains it needs passes every one of those checks.
  lt::ChildProcess good({lt::bin("scenario"), "run", lt::source("test/scenarios/effort_trajectory_goal.scenario.yaml")});
  EXPECT_EQ(good.wait(60), 0) << good.output();
  fs::remove_all(dir);
}

TEST(ScenarioRunner, AFolderRunsOnePerCpuIntoATableAndJUnitWithEveryOutcomeNamed) {
  const fs::path dir = scratch("folder");
  const std::string tuned = lt::source("config/turret_bot.yaml");
  write(dir / "a_holds.scenario.yaml", turret(tuned));
  write(dir / "b_absent.scenario.yaml", "requires: [/no/such/robot/here.urdf]\n");
  write(dir / "c_typo.scenario.yaml", turret(tuned) + "duraton: 3\n");
  write(dir / "d_overruns.scenario.yaml", turret(tuned, 600));
  write(dir / "not_a_scenario.yaml", "ignored: true\n");
  lt::ChildProcess run({lt::bin("scenario"), "run", dir.string(), "--jobs", "2", "--timeout", "3", "--junit",
                        (dir / "out.xml").string()});
  ASSERT_EQ(run.wait(60), 2) << run.output();  // one could not run
  const std::string out = run.output();
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(\na_holds +passed +2\.000 +[0-9.]+ +3/3\n)"))) << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(\nb_absent +skipped .*\n +skipped: needs /no/such/robot/here.urdf\n)")))
      << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(\nc_typo +ERROR .*\n +error: .*c_typo.scenario.yaml:[0-9]+: 'duraton': unknown key)")))
      << out;
  EXPECT_TRUE(std::regex_search(out, std::regex(R"(\nd_overruns +ERROR .*\n +error: did not finish within 3 s of wall time \(stopped\))")))
      << out;
  EXPECT_NE(out.find("4 scenario(s): 1 passed, 0 failed, 2 error(s), 1 skipped"), std::string::npos) << out;
  EXPECT_EQ(out.find("not_a_scenario"), std::string::npos) << out;
  const std::string xml = read(dir / "out.xml");
  EXPECT_NE(xml.find(R"(tests="4" failures="0" errors="2" skipped="1")"), std::string::npos) << xml;
  EXPECT_NE(xml.find(R"(<skipped message="needs /no/such/robot/here.urdf"/>)"), std::string::npos) << xml;
  // Only skipped: exit 0, or the code ctest reads as skipped when asked.
  lt::ChildProcess skipped({lt::bin("scenario"), "run", (dir / "b_absent.scenario.yaml").string(), "--skipped-exit", "77"});
  EXPECT_EQ(skipped.wait(30), 77) << skipped.output();
  fs::remove_all(dir);
}

TEST(ScenarioRunner, AGoldenLogReplaysBitForBitAndAChangedGainFailsIt) {
  const fs::path dir = scratch("golden");
  write(dir / "gains.yaml", read(lt::source("config/turret_bot.yaml")));
  write(dir / "hold.scenario.yaml", turret(dir / "gains.yaml") + "golden: hold.golden.lcmlog\n");
  lt::ChildProcess missing({lt::bin("scenario"), "run", (dir / "hold.scenario.yaml").string()});
  ASSERT_EQ(missing.wait(60), 1) << missing.output();
  EXPECT_NE(missing.output().find("no golden log " + (dir / "hold.golden.lcmlog").string() + ": record it with `scenario record"),
            std::string::npos) << missing.output();

  lt::ChildProcess record({lt::bin("scenario"), "record", (dir / "hold.scenario.yaml").string(),
                           (dir / "hold.golden.lcmlog").string()});
  ASSERT_EQ(record.wait(60), 0) << record.output();
  EXPECT_NE(record.output().find("recorded "), std::string::npos) << record.output();
  lt::ChildProcess again({lt::bin("scenario"), "run", "-v", (dir / "hold.scenario.yaml").string()});
  ASSERT_EQ(again.wait(60), 0) << again.output();
  EXPECT_TRUE(std::regex_search(again.output(), std::regex(R"(pass replays its golden log \(.*hold.golden.lcmlog\): identical: 2001 hardware states replayed, every compared message bit for bit)")))
      << again.output();
  // The log replays on its own too, closed loop, from the configuration it recorded.
  lt::ChildProcess replay({lt::bin("replay"), (dir / "hold.golden.lcmlog").string(), "--sim"});
  EXPECT_EQ(replay.wait(60), 0) << replay.output();

  // j2's simulated p from 1 to 1.5: the scenario's own checks still pass, the golden log does not.
  std::string gains = read(dir / "gains.yaml");
  const size_t j2 = gains.find("j2:", gains.find("pid_gains"));
  ASSERT_NE(j2, std::string::npos);
  gains.replace(gains.find("p: 1", j2), 4, "p: 1.5");
  write(dir / "gains.yaml", gains);
  lt::ChildProcess changed({lt::bin("scenario"), "run", (dir / "hold.scenario.yaml").string()});
  ASSERT_EQ(changed.wait(60), 1) << changed.output();
  EXPECT_TRUE(std::regex_search(changed.output(), std::regex(R"(FAIL replays its golden log \(.*\): diverged: first on joint_states at t=0\.[0-9]+ s, position\[j[12]\]: recorded .*, replayed )")))
      << changed.output();
  EXPECT_TRUE(std::regex_search(changed.output(), std::regex(R"(\nhold +FAILED +2\.000 +[0-9.]+ +3/4\n)"))) << changed.output();
  fs::remove_all(dir);
}

TEST(ScenarioRunner, AnInputTheControllerManagerRefusesFailsWhereItIsWritten) {
  const fs::path dir = scratch("refused");
  write(dir / "switch.scenario.yaml",
        turret(lt::source("config/turret_bot.yaml"), 2, "  - {at: 1, switch: {start: [j3_controller]}}\n"));
  lt::ChildProcess run({lt::bin("scenario"), "run", (dir / "switch.scenario.yaml").string()});
  ASSERT_EQ(run.wait(60), 1) << run.output();
  EXPECT_TRUE(std::regex_search(run.output(), std::regex(R"(FAIL input accepted \(.*switch.scenario.yaml:8: switch\): .*j3_controller)")))
      << run.output();
  fs::remove_all(dir);
}

// A disturbance is an input of sim_server's: its recording replays closed loop with the wrench served at the step
// its answer names (without it, j1 would not have been pushed 0.2 m off and the replay would diverge); a pause or a
// reset is refused, pointing at the open loop.
TEST(ScenarioRunner, AWrenchReplaysClosedLoopBitForBitAndAResetIsRefusedSayingWhy) {
  const fs::path dir = scratch("wrench");
  lt::ChildProcess record({lt::bin("scenario"), "record", lt::source("test/scenarios/turret_wrench_disturbance.scenario.yaml"),
                           (dir / "w.lcmlog").string()});
  ASSERT_EQ(record.wait(60), 0) << record.output();
  lt::ChildProcess replay({lt::bin("replay"), (dir / "w.lcmlog").string(), "--sim"});
  ASSERT_EQ(replay.wait(60), 0) << replay.output();
  EXPECT_NE(replay.output().find("identical: 8001 hardware states replayed"), std::string::npos) << replay.output();
  EXPECT_NE(replay.output().find("joint_states: 481 compared, 0 differ"), std::string::npos) << replay.output();

  lt::ChildProcess reset_record({lt::bin("scenario"), "record", lt::source("test/scenarios/turret_pause_reset.scenario.yaml"),
                                 (dir / "r.lcmlog").string()});
  ASSERT_EQ(reset_record.wait(60), 0) << reset_record.output();
  lt::ChildProcess refused({lt::bin("replay"), (dir / "r.lcmlog").string(), "--sim"});
  ASSERT_EQ(refused.wait(60), 2) << refused.output();
  EXPECT_NE(refused.output().find("sim_server was asked to reset (request 1001): a closed loop replays wrenches only"),
            std::string::npos) << refused.output();
  fs::remove_all(dir);
}

// A goal check judges the last goal sent by its time: an earlier goal's success does not pass for a later goal still
// under way.
TEST(ScenarioRunner, AGoalCheckJudgesTheLastGoalSentNotAnEarlierOnesResult) {
  const fs::path dir = scratch("goals");
  write(dir / "goals.scenario.yaml",
        "launch: " + lt::source("config/turret_bot_trajectory.launch.yaml") + "\nduration: 4\ntimeline:\n"
        "  - {at: 0.5, goal: {controller: trajectory_controller, joint_names: [j1, j2], points: [{positions: [0.2, 0.2], time_from_start: 1}]}}\n"
        "  - {at: 3, goal: {controller: trajectory_controller, joint_names: [j1, j2], points: [{positions: [0.4, 0.4], time_from_start: 30}]}}\n"
        "checks:\n  - {goal: trajectory_controller, result: SUCCEEDED, by: 2.9}\n"
        "  - {goal: trajectory_controller, result: SUCCEEDED}\n  - {goal: trajectory_controller, result: ACTIVE}\n");
  lt::ChildProcess run({lt::bin("scenario"), "run", "-v", (dir / "goals.scenario.yaml").string()});
  ASSERT_EQ(run.wait(60), 1) << run.output();
  EXPECT_TRUE(std::regex_search(run.output(), std::regex(R"(pass goal of trajectory_controller SUCCEEDED by t=2.9 s \(.*\): goal 1000 SUCCEEDED)")))
      << run.output();
  EXPECT_TRUE(std::regex_search(run.output(), std::regex(R"(FAIL goal of trajectory_controller SUCCEEDED at the end \(.*\): goal 1001: no result on trajectory_controller/result \(still ACTIVE\))")))
      << run.output();
  EXPECT_NE(run.output().find("pass goal of trajectory_controller ACTIVE at the end"), std::string::npos) << run.output();
  fs::remove_all(dir);
}
