// send-trajectory's waypoint readers (--point, YAML, CSV), the checks before a
// goal is sent, the message built, and the controller check: good input and
// the exact words of each error.
#include "tools/lib/clients/trajectory_goal.hpp"

#include <gtest/gtest.h>

#include "description/robot_model.hpp"
#include "lcm_control/trajectory_status_t.hpp"

using namespace lcm_control;
using namespace lcm_control::tools;

namespace {

// The problems of the ModelError `f` throws, one per line ("" if it does not throw).
template <class F>
std::string problems_of(F&& f) {
  try {
    f();
  } catch (const ModelError& e) {
    std::string all;
    for (const auto& p : e.problems()) all += p + "\n";
    return all;
  }
  return "";
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

TrajectoryGoal checked(TrajectoryGoal g, const std::string& joints) {
  set_joints_from_flag(g, joints);
  check_goal(g);
  return g;
}

}  // namespace

TEST(TrajectoryGoal, PointArgsWithAndWithoutVelocities) {
  const TrajectoryGoal g = checked(parse_point_args({"2.0:0.1,0.2,0.3", "4:-0.5, 0 ,1e-1:1,2,3"}), "a,b,c");
  ASSERT_EQ(g.points.size(), 2u);
  EXPECT_EQ(g.joints, (std::vector<std::string>{"a", "b", "c"}));
  EXPECT_EQ(g.points[0].time, 2.0);
  EXPECT_EQ(g.points[0].positions, (std::vector<double>{0.1, 0.2, 0.3}));
  EXPECT_TRUE(g.points[0].velocities.empty());
  EXPECT_EQ(g.points[1].time, 4.0);
  EXPECT_EQ(g.points[1].positions, (std::vector<double>{-0.5, 0.0, 0.1}));
  EXPECT_EQ(g.points[1].velocities, (std::vector<double>{1, 2, 3}));
  EXPECT_EQ(g.points[1].where, "--point 2 ('4:-0.5, 0 ,1e-1:1,2,3')");
}

TEST(TrajectoryGoal, BadPointArgsNameThePointAndTheValue) {
  const std::string p = problems_of([] { parse_point_args({"2", "x:1", "3:0.1,,0.3", "4:0.1,abc", "5:nan", "6:1:2:3"}); });
  EXPECT_TRUE(has(p, "--point 1 ('2'): expected TIME:POSITIONS or TIME:POSITIONS:VELOCITIES, e.g. 2.0:0.1,0.2")) << p;
  EXPECT_TRUE(has(p, "--point 2 ('x:1'): time 'x' is not a number; the field before the first ':' is the time")) << p;
  EXPECT_TRUE(has(p, "--point 3 ('3:0.1,,0.3'): value 2 of the positions is empty; give one number per joint")) << p;
  EXPECT_TRUE(has(p, "--point 4 ('4:0.1,abc'): 'abc' (value 2 of the positions) is not a finite number")) << p;
  EXPECT_TRUE(has(p, "--point 5 ('5:nan'): 'nan' (value 1 of the positions) is not a finite number")) << p;
  EXPECT_TRUE(has(p, "--point 6 ('6:1:2:3'): expected TIME:POSITIONS")) << p;
}

TEST(TrajectoryGoal, ChecksCountsTimesAndJointNames) {
  std::string p = problems_of([] { checked(parse_point_args({"2:0.1,0.2", "1:0,0,0", "1:0,0:1"}), "a,b"); });
  EXPECT_TRUE(has(p, "--point 2 ('1:0,0,0'): 3 positions for 2 joints (a, b; from --joints); give one value per joint"))
      << p;
  EXPECT_TRUE(has(p, "--point 2 ('1:0,0,0'): time 1 must be after the previous point's 2 (times count from the start "
                     "and increase)"))
      << p;
  EXPECT_TRUE(has(p, "--point 3 ('1:0,0:1'): 1 velocity for 2 joints (a, b; from --joints); give none or one per joint"))
      << p;
  EXPECT_TRUE(has(p, "--point 3 ('1:0,0:1'): time 1 must be after the previous point's 2")) << p;

  p = problems_of([] { checked(parse_point_args({"0:0.1"}), "a"); });
  EXPECT_EQ(p, "--point 1 ('0:0.1'): time 0 must be > 0 (seconds from the start; at 0 the joints are where they are)\n");
  p = problems_of([] { checked(parse_point_args({"1:0.1,0.2"}), "a,a"); });
  EXPECT_EQ(p, "--joints: joint 'a' is listed twice\n");
  p = problems_of([] { checked(parse_point_args({"1:0.1,0.2"}), "a,"); });
  EXPECT_EQ(p, "--joints: joint 2 has an empty name\n");
  p = problems_of([] { check_goal(parse_point_args({})); });
  EXPECT_TRUE(has(p, "no joints: name them with --joints")) << p;
  EXPECT_TRUE(has(p, "no points: give --point TIME:POSITIONS, --file or --csv")) << p;

  TrajectoryGoal nan_goal = parse_point_args({"1:0.5"});
  nan_goal.points[0].positions[0] = std::nan("");
  p = problems_of([&] { checked(nan_goal, "a"); });
  EXPECT_EQ(p, "--point 1 ('1:0.5'): nan is not a finite number\n");
}

TEST(TrajectoryGoal, YamlInJointTrajectorysLayoutWithRosDurations) {
  const std::string yaml = R"(header: {seq: 0, frame_id: ''}
joint_names: [j1, j2]
points:
  - positions: [0.1, 0.2]
    velocities: [0, 0]
    accelerations: []
    effort: []
    time_from_start: {secs: 1, nsecs: 500000000}
  - positions: [0.3, -0.3]
    time_from_start: 3
  - {positions: [0, 0], time_from_start: {sec: 4, nanosec: 250000000}}
)";
  const TrajectoryGoal g = parse_goal_yaml(yaml, "goal.yaml");
  check_goal(g);
  EXPECT_EQ(g.joints, (std::vector<std::string>{"j1", "j2"}));
  EXPECT_EQ(g.joints_where, "goal.yaml:2: joint_names");
  ASSERT_EQ(g.points.size(), 3u);
  EXPECT_DOUBLE_EQ(g.points[0].time, 1.5);
  EXPECT_EQ(g.points[0].velocities, (std::vector<double>{0, 0}));
  EXPECT_EQ(g.points[1].positions, (std::vector<double>{0.3, -0.3}));
  EXPECT_DOUBLE_EQ(g.points[2].time, 4.25);
  EXPECT_EQ(g.points[1].where, "goal.yaml:9: point 2");

  // Without joint_names the goal is for the controller's joints; --joints may name them.
  const TrajectoryGoal bare = parse_goal_yaml("points: [{positions: [1], time_from_start: 1}]", "bare.yaml");
  EXPECT_TRUE(bare.joints.empty());
  EXPECT_EQ(checked(bare, "j2").joints, (std::vector<std::string>{"j2"}));
}

TEST(TrajectoryGoal, BadYamlNamesTheLineAndTheKey) {
  std::string p = problems_of([] { parse_goal_yaml("joint_names: [a\npoints: [", "broken.yaml"); });
  EXPECT_TRUE(has(p, "broken.yaml:")) << p;
  EXPECT_TRUE(has(p, ": malformed YAML: ")) << p;

  p = problems_of([] { parse_goal_yaml("- 1\n- 2\n", "list.yaml"); });
  EXPECT_TRUE(has(p, "list.yaml: expected a map with joint_names and points")) << p;

  p = problems_of([] {
    parse_goal_yaml(R"(jonit_names: [a]
points:
  - positions: [0.1, x]
    time_from_start: 1
  - position: [0.1]
    time_from_start: {secs: 2, nsec: 5}
  - positions: [0.1]
    effort: [3]
  - 7
)",
                    "goal.yaml");
  });
  EXPECT_TRUE(has(p, "goal.yaml:1: unknown key 'jonit_names' in the trajectory (valid keys: joint_names, points, "
                     "header); did you mean 'joint_names'?"))
      << p;
  EXPECT_TRUE(has(p, "goal.yaml:3: point 1: positions value 2 ('x') is not a finite number")) << p;
  EXPECT_TRUE(has(p, "goal.yaml:5: unknown key 'position' in point 2 (valid keys: positions, velocities, "
                     "accelerations, effort, time_from_start); did you mean 'positions'?"))
      << p;
  EXPECT_TRUE(has(p, "goal.yaml:5: point 2: no positions; add positions: [...] with one value per joint")) << p;
  EXPECT_TRUE(has(p, "goal.yaml:6: unknown key 'nsec' in time_from_start (valid keys: secs, nsecs, sec, nanosec); did "
                     "you mean 'nsecs'?"))
      << p;
  EXPECT_TRUE(has(p, "goal.yaml:7: point 3: effort is not used by a JointTrajectoryController; remove it")) << p;
  EXPECT_TRUE(has(p, "goal.yaml:7: point 3: no time_from_start; add time_from_start: SECONDS (or {secs: S, nsecs: N})"))
      << p;
  EXPECT_TRUE(has(p, "goal.yaml:9: point 4: expected a map {positions: [...], time_from_start: SECONDS}")) << p;

  p = problems_of([] { parse_goal_yaml("joint_names: [a]\n", "empty.yaml"); });
  EXPECT_EQ(p, "empty.yaml: no 'points'; add points: [{positions: [...], time_from_start: SECONDS}]\n");

  // Checked against its own joint_names: the point's line.
  p = problems_of([] {
    check_goal(parse_goal_yaml("joint_names: [a, b]\npoints:\n  - {positions: [1], time_from_start: 2}\n", "n.yaml"));
  });
  EXPECT_EQ(p, "n.yaml:3: point 1: 1 position for 2 joints (a, b; from n.yaml:1: joint_names); give one value per "
               "joint\n");
}

TEST(TrajectoryGoal, CsvWithHeaderCommentsAndBlankLines) {
  const TrajectoryGoal g = parse_goal_csv("# a square\ntime,j1,j2\n1.0,0.1,0.2\n\n2.5, 0.3 ,-0.3\r\n", "goal.csv");
  check_goal(g);
  EXPECT_EQ(g.joints, (std::vector<std::string>{"j1", "j2"}));
  EXPECT_EQ(g.joints_where, "goal.csv:2: header");
  ASSERT_EQ(g.points.size(), 2u);
  EXPECT_EQ(g.points[1].time, 2.5);
  EXPECT_EQ(g.points[1].positions, (std::vector<double>{0.3, -0.3}));
  EXPECT_EQ(g.points[1].where, "goal.csv:5");
}

TEST(TrajectoryGoal, BadCsvNamesTheLineAndTheColumn) {
  EXPECT_EQ(problems_of([] { parse_goal_csv("t,j1\n1,2\n", "a.csv"); }),
            "a.csv:1: the header must be time,<joint>,<joint>,... (the first column is the time from the start in "
            "seconds), not 't,j1'\n");
  EXPECT_EQ(problems_of([] { parse_goal_csv("time\n1\n", "b.csv"); }),
            "b.csv:1: the header names no joint; write time,<joint>,<joint>,...\n");
  EXPECT_EQ(problems_of([] { parse_goal_csv("", "c.csv"); }),
            "c.csv: empty; the first line must be the header time,<joint>,<joint>,...\n");
  EXPECT_EQ(problems_of([] { parse_goal_csv("time,j1\n", "d.csv"); }),
            "d.csv: no rows after the header; add one row per point: TIME,<position per joint>\n");
  const std::string p = problems_of([] { parse_goal_csv("time,j1,j2\n1,0.1\n2,0.1,x\nsoon,0,0\n", "e.csv"); });
  EXPECT_EQ(p,
            "e.csv:2: 2 values for the 3 columns of the header (time,j1,j2); give the time and one position per joint\n"
            "e.csv:3: 'x' (column 'j2') is not a finite number\n"
            "e.csv:4: time 'soon' is not a number of seconds\n");
  // Times are checked with the rest, naming the row.
  EXPECT_EQ(problems_of([] { check_goal(parse_goal_csv("time,j1\n2,0\n2,1\n", "f.csv")); }),
            "f.csv:3: time 2 must be after the previous point's 2 (times count from the start and increase)\n");
}

TEST(TrajectoryGoal, JointsFromTheFlagMustAgreeWithTheFile) {
  TrajectoryGoal g = parse_goal_csv("time,j1,j2\n1,0,0\n", "g.csv");
  EXPECT_NO_THROW(set_joints_from_flag(g, "j1, j2"));
  g = parse_goal_csv("time,j1,j2\n1,0,0\n", "g.csv");
  EXPECT_EQ(problems_of([&] { set_joints_from_flag(g, "j2,j1"); }),
            "--joints j2,j1 does not match g.csv:1: header (j1,j2); name the joints in one place\n");
}

TEST(TrajectoryGoal, RelativeOffsetsAndTheMessage) {
  TrajectoryGoal g = checked(parse_point_args({"1:0.1,0.2", "2:0,0:0.5,0"}), "j1,j2");
  add_offsets(g, {1.0, -1.0});
  const joint_trajectory_t m = to_message(g, 42, 1000);
  EXPECT_EQ(m.goal_id, 42);
  EXPECT_EQ(m.utime, 1000);
  EXPECT_EQ(m.num_joints, 2);
  EXPECT_EQ(m.joint_names, (std::vector<std::string>{"j1", "j2"}));
  ASSERT_EQ(m.num_points, 2);
  ASSERT_EQ(m.points.size(), 2u);
  EXPECT_EQ(m.points[0].time_from_start, 1.0);
  EXPECT_EQ(m.points[0].num_positions, 2);
  EXPECT_EQ(m.points[0].positions, (std::vector<double>{1.1, -0.8}));
  EXPECT_EQ(m.points[0].num_velocities, 0);
  EXPECT_EQ(m.points[1].positions, (std::vector<double>{1.0, -1.0}));
  EXPECT_EQ(m.points[1].num_velocities, 2);
  EXPECT_EQ(m.points[1].velocities, (std::vector<double>{0.5, 0}));
  EXPECT_EQ(m.points[1].num_accelerations, 0);
  // The message encodes (its counts match its arrays).
  std::vector<uint8_t> buf(size_t(m.getEncodedSize()));
  EXPECT_EQ(m.encode(buf.data(), 0, int(buf.size())), int(buf.size()));
}

TEST(TrajectoryGoal, ControllerNamesAsRosUsersWriteThem) {
  EXPECT_EQ(controller_name("arm_controller"), "arm_controller");
  EXPECT_EQ(controller_name("/arm_controller"), "arm_controller");
  EXPECT_EQ(controller_name("/arm_controller/command"), "arm_controller");
  EXPECT_EQ(controller_name("arm_controller/"), "arm_controller");
  EXPECT_EQ(controller_name("/"), "");
  EXPECT_EQ(status_name(trajectory_status_t::GOAL_TOLERANCE_VIOLATED), "GOAL_TOLERANCE_VIOLATED");
  EXPECT_EQ(status_name(trajectory_status_t::REJECTED), "REJECTED");
  EXPECT_EQ(status_name(9), "status 9");
}

TEST(TrajectoryGoal, TheControllerMustBeARunningTrajectoryController) {
  auto info = [](std::string name, std::string type, std::string state, std::string command_type) {
    controller_info_t c{};
    c.name = std::move(name);
    c.type = std::move(type);
    c.state = std::move(state);
    c.joints = {"j1", "j2"};
    c.num_joints = 2;
    c.command_channel = command_type.empty() ? "" : "command";
    c.command_type = std::move(command_type);
    return c;
  };
  const std::vector<controller_info_t> listed = {
      info("joint_state_controller", "joint_state_controller/JointStateController", "running", ""),
      info("trajectory_controller", "position_controllers/JointTrajectoryController", "running", "joint_trajectory_t"),
      info("idle_trajectory", "effort_controllers/JointTrajectoryController", "initialized", "joint_trajectory_t"),
      info("j1_controller", "position_controllers/JointPositionController", "running", "float64_t")};
  EXPECT_EQ(trajectory_controller(listed, "trajectory_controller").joints, (std::vector<std::string>{"j1", "j2"}));
  auto error_of = [&](const std::string& name) {
    try {
      trajectory_controller(listed, name);
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(error_of("trajectory_controler"),
            "no controller 'trajectory_controler' in the controller manager (loaded: joint_state_controller, "
            "trajectory_controller, idle_trajectory, j1_controller): load and start it with `spawner "
            "trajectory_controler` (a controller of the ros_control YAML); did you mean 'trajectory_controller'?");
  EXPECT_EQ(error_of("idle_trajectory"),
            "'idle_trajectory' is loaded but initialized, not running: start it with `cmctl start idle_trajectory`");
  EXPECT_EQ(error_of("j1_controller"),
            "j1_controller takes float64_t on j1_controller/command; joint_trajectory_t was given: use turret-cmd "
            "j1_controller VALUE");
  EXPECT_EQ(error_of("joint_state_controller"),
            "joint_state_controller (joint_state_controller/JointStateController) takes no commands (it only reads the "
            "joints); joint_trajectory_t was given on joint_state_controller/command: command a controller that drives "
            "the joints instead (cmctl list)");
  EXPECT_TRUE(has([&] {
    try {
      trajectory_controller({}, "x");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  }(), "no controller 'x' in the controller manager (none loaded): load and start it with `spawner x`"));
}
