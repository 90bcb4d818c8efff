// Trajectory goals as send-trajectory reads them: waypoints from --point
// arguments, a YAML file (trajectory_msgs/JointTrajectory's layout) or a CSV
// file, checked before anything is sent, the joint_trajectory_t built from
// them, and the check that the controller can take it. Bad input is a
// ModelError naming the --point, or the file and line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "lcm_control/controller_info_t.hpp"
#include "lcm_control/joint_trajectory_t.hpp"

namespace lcm_control::tools {

struct GoalPoint {
  double time = 0;  // seconds from the start of the goal
  std::vector<double> positions;
  std::vector<double> velocities;     // none, or one per joint
  std::vector<double> accelerations;  // none, or one per joint (with velocities)
  std::string where;                  // "--point 2 ('2:0.1,0.2')", "goal.yaml:7: point 2", "goal.csv:3"
};

struct TrajectoryGoal {
  std::vector<std::string> joints;  // empty: not named by the input (the controller's are used)
  std::string joints_where;         // "--joints", "goal.yaml:1: joint_names", ...
  std::vector<GoalPoint> points;
};

// --point values, each "TIME:POSITIONS[:VELOCITIES]" with comma-separated lists,
// e.g. "2:0.1,0.2" or "2:0.1,0.2:0,0".
TrajectoryGoal parse_point_args(const std::vector<std::string>& args);
// A YAML map {joint_names: [...], points: [{positions, velocities, accelerations,
// time_from_start}]}; time_from_start in seconds or ROS's {secs, nsecs} ({sec, nanosec}).
// `path` is only for messages.
TrajectoryGoal parse_goal_yaml(const std::string& text, const std::string& path);
// A header `time,<joint>,...` and one row per point; blank lines and lines starting with '#' are skipped.
TrajectoryGoal parse_goal_csv(const std::string& text, const std::string& path);

// Sets the joints from --joints (comma-separated); if the input named them too, both lists must agree.
void set_joints_from_flag(TrajectoryGoal& goal, const std::string& joints_flag);

// Every problem at once: joints named once each, one value per joint in every
// point, times > 0 and strictly increasing, finite numbers.
void check_goal(const TrajectoryGoal& goal);

// Positions become offsets from `start` (one per joint, in goal.joints' order).
void add_offsets(TrajectoryGoal& goal, const std::vector<double>& start);

joint_trajectory_t to_message(const TrajectoryGoal& goal, int64_t goal_id, int64_t utime);

// `name` among the controllers the manager lists, if it is running and takes joint_trajectory_t goals (a
// JointTrajectoryController); else std::runtime_error saying what to do (command_check.hpp's commandable); `prefix`
// is the namespace prefix of the channels it names.
const controller_info_t& trajectory_controller(const std::vector<controller_info_t>& listed, const std::string& name,
                                              const std::string& prefix = "");

// The controller a ROS user names: "/arm_controller", "/arm_controller/command" -> "arm_controller".
std::string controller_name(const std::string& target);

// trajectory_status_t's constant names: "SUCCEEDED", "GOAL_TOLERANCE_VIOLATED", ...
std::string status_name(int8_t status);

}  // namespace lcm_control::tools
