// Scenario files read (tools/lib/scenarios/scenario.hpp): the launch they embed, the timeline's inputs built into
// the messages they will publish, the checks, and every mistake named by file, line and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "description/robot_model.hpp"
#include "test/support/process.hpp"
#include "tools/lib/messages/message_json.hpp"
#include "tools/lib/messages/message_text.hpp"
#include "tools/lib/scenarios/scenario.hpp"

using namespace lcm_control;
using namespace lcm_control::tools;
namespace fs = std::filesystem;

namespace {

std::string write_scenario(const std::string& name, const std::string& text) {
  const fs::path dir = fs::temp_directory_path() / ("scenario_file_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / (name + ".scenario.yaml");
  std::ofstream(p) << text;
  return p.string();
}

std::string robot() {
  return "urdf: " + lcm_control::testing::source("config/turret_bot.urdf") + "\nconfig: " + lcm_control::testing::source("config/turret_bot.yaml") +
         "\ncontrollers: [joint_state_controller, j1_controller]\n";
}

std::string problems(const std::string& path) {
  try {
    read_scenario(path);
  } catch (const ModelError& e) {
    std::string all;
    for (const auto& p : e.problems()) all += p + "\n";
    return all;
  }
  return "";
}

}  // namespace

TEST(ScenarioFile, ALaunchWithATimelineAndChecksIsReadIntoMessagesAndChecks) {
  const std::string path = write_scenario("good", robot() + R"(duration: 3
timeline:
  - {at: 2, command: {controller: j1_controller, value: 0.25}}
  - {at: 0.5, every: 0.5, until: 1.5, cmd_vel: {controller: base, linear: 0.2, angular: 0.1}}
  - {at: 1, switch: {start: [j1_controller], stop: [j2_controller]}}
  - {at: 1, goal: {controller: arm, joint_names: [j1, j2], points: [{positions: [0.1, 0.2], time_from_start: 1}]}}
  - {at: 2.5, gripper: {controller: hand, position: 0.02}}
checks:
  - {field: "position[j1]", at: 3, near: 0.25, tolerance: 0.01}
  - {tracking: j1, command: j1_controller/command, window: [2.5, 3], rms_below: 0.01}
  - {goal: arm, by: 3}
  - {odometry: base, channel: base/odometry, within: 0.05}
)");
  const Scenario s = read_scenario(path);
  EXPECT_EQ(s.name, "good");
  EXPECT_EQ(s.launch.mode, "lockstep");
  EXPECT_EQ(s.launch.controllers, (std::vector<std::string>{"joint_state_controller", "j1_controller"}));
  EXPECT_DOUBLE_EQ(s.duration, 3);
  ASSERT_EQ(s.timeline.size(), 7u);  // cmd_vel at 0.5, 1, 1.5; then in time order, stable
  EXPECT_DOUBLE_EQ(s.timeline[0].at, 0.5);
  EXPECT_EQ(s.timeline[0].channel, "base/cmd_vel");
  EXPECT_EQ(s.timeline[1].channel, "base/cmd_vel");
  EXPECT_EQ(s.timeline[2].fields["request_id"], 1002);
  EXPECT_EQ(s.timeline[3].fields["goal_id"], 1003);
  EXPECT_EQ(s.timeline[2].channel, "controller_manager/request");
  EXPECT_EQ(s.timeline[3].channel, "arm/command");
  EXPECT_EQ(s.timeline[3].type, "joint_trajectory_t");
  EXPECT_EQ(s.timeline[4].at, 1.5);
  EXPECT_EQ(s.timeline[5].type, "float64_t");
  EXPECT_EQ(s.timeline[6].type, "gripper_command_t");
  EXPECT_EQ(s.timeline[6].channel, "hand/command");
  EXPECT_EQ(s.timeline[6].fields["goal_id"], 1006);  // every request and goal its own id, 1000 + its place in time
  const std::vector<uint8_t> cmd = message_from_json(s.timeline[5].type, s.timeline[5].fields, 2000000);
  EXPECT_EQ(cmd, build_message("float64_t", {"data=0.25"}, 2000000));
  ASSERT_EQ(s.checks.size(), 4u);
  EXPECT_EQ(s.checks[0].kind, Check::Kind::Value);
  EXPECT_EQ(s.checks[0].channel, "joint_states");
  EXPECT_EQ(s.checks[0].name, "joint_states position[j1] at t=3 s");
  EXPECT_EQ(s.checks[1].kind, Check::Kind::Tracking);
  EXPECT_EQ(s.checks[2].channel, "arm/result");
  EXPECT_EQ(s.checks[2].result, "SUCCEEDED");
  EXPECT_EQ(s.checks[3].channel, "base/odometry");
}

TEST(ScenarioFile, EveryMistakeIsNamedByFileLineAndKey) {
  const std::string path = write_scenario("bad", robot() + R"(duration: 2
timeline:
  - {at: 1, command: {controller: j1_controller}}
  - {at: 3, e_stop: true}
  - {at: 1, wiggle: {}}
  - {at: 1, every: 0.5, cmd_vel: {controller: base, linear: 1}}
  - {command: {controller: j1_controller, value: 1}}
checks:
  - {field: "position[j1]", at: 1}
  - {tracking: j1, rms_below: 0.1}
  - {at: 1}
)");
  const std::string all = problems(path);
  EXPECT_NE(all.find(path + ":6: command: needs `value: X`"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":8: timeline.wiggle: unknown key"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":9: timeline: `every: S`"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":10: timeline: needs `at:`"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":12: check: needs `near:` with `tolerance:`, or `min:` and/or `max:`"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":13: check: tracking needs `command:`"), std::string::npos) << all;
  EXPECT_NE(all.find(path + ":14: check: names one thing to check"), std::string::npos) << all;
  EXPECT_NE(all.find("at 3 s is after the scenario's end (2 s)"), std::string::npos) << all;
}

TEST(ScenarioFile, AScenarioWithoutChecksOrDurationIsRefusedAndAnUnknownLaunchKeyNamed) {
  const std::string all = problems(write_scenario("empty", robot() + "spawn_me: [x]\n"));
  EXPECT_NE(all.find("duration: is required"), std::string::npos) << all;
  EXPECT_NE(all.find("checks: needs at least one check: a scenario that checks nothing cannot fail"), std::string::npos) << all;
  const std::string launch = problems(write_scenario("unknown", robot() + "spawn_me: [x]\nduration: 1\nchecks: [{goal: a}]\n"));
  EXPECT_NE(launch.find("'spawn_me': unknown key"), std::string::npos) << launch;
}

TEST(ScenarioFile, APauseIsAPauseAndAResumeAndAResetCarriesItsStartPose) {
  const Scenario s = read_scenario(write_scenario("pause", robot() + R"(duration: 5
timeline:
  - {at: 1, pause: 0.5}
  - {at: 3, reset: {j1: 0.2}}
checks: [{field: "position[j1]", at: 5, min: 0}]
)"));
  ASSERT_EQ(s.timeline.size(), 3u);
  EXPECT_TRUE(s.pauses_or_resets);
  EXPECT_EQ(s.timeline[0].fields["op"], 1);  // PAUSE at 1, RESUME at 1.5
  EXPECT_DOUBLE_EQ(s.timeline[1].at, 1.5);
  EXPECT_EQ(s.timeline[1].fields["op"], 2);
  EXPECT_EQ(s.timeline[2].channel, "sim_server/request");
  EXPECT_EQ(s.timeline[2].fields["joint"], nlohmann::json::array({"j1"}));
  const std::string golden = problems(write_scenario("pause_golden", robot() + R"(duration: 5
golden: g.lcmlog
timeline: [{at: 1, reset: {}}]
checks: [{field: "position[j1]", at: 5, min: 0}]
)"));
  EXPECT_NE(golden.find("golden: a scenario that pauses or resets the simulation has no golden log yet"), std::string::npos)
      << golden;
  // A repeated wrench is a request of its own each time (one id would be answered again, not done again).
  const Scenario repeated = read_scenario(write_scenario("wrenches", robot() + R"(duration: 5
timeline: [{at: 1, every: 1, until: 3, wrench: {link: slider, force: [0, 10, 0], duration: 0.1}}]
checks: [{field: "position[j1]", at: 5, min: 0}]
)"));
  ASSERT_EQ(repeated.timeline.size(), 3u);
  EXPECT_NE(repeated.timeline[0].fields["request_id"], repeated.timeline[1].fields["request_id"]);
  // A check after the end, a result that is none, two times for one check.
  const std::string checks = problems(write_scenario("checks", robot() + R"(duration: 5
checks:
  - {field: "position[j1]", at: 6, min: 0}
  - {goal: arm, result: SUCCEDED, at: 1, by: 2}
)"));
  EXPECT_NE(checks.find(":6: check: t=6 s is after the scenario's end (5 s)"), std::string::npos) << checks;
  EXPECT_NE(checks.find(":7: result: 'SUCCEDED' is no result; one of"), std::string::npos) << checks;
  EXPECT_NE(checks.find(":7: check: one of `at:`, `window:` or `by:`"), std::string::npos) << checks;
}

TEST(ScenarioFile, ARobotNotInThisCheckoutSkipsTheScenarioUnread) {
  const Scenario s = read_scenario(write_scenario("absent", "requires: [/no/such/robot.urdf]\nthis: is not read\n"));
  ASSERT_EQ(s.requires_files.size(), 1u);
  EXPECT_EQ(s.requires_files[0], "/no/such/robot.urdf");
  EXPECT_EQ(scenario_name("a/b/c.scenario.yaml"), "c");
}
