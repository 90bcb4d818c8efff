// What a launch file asks launch to start: the one result both readers (launch_yaml.cpp, launch_ros_xml.cpp) fill
// in, and the bounds launch checks its values against.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace lcm_control::tools {

struct ProcessSpec {
  std::string name;               // output prefix
  std::vector<std::string> argv;  // argv[0]: a program next to launch, on PATH, or a path
  bool required = true;           // its exit stops everything
};

// A command source registered in the controller manager once the controllers
// run (`commands:`): expressions in i and t ticking on sim time.
struct CommandSpec {
  std::string target;             // controller
  std::vector<std::string> expr;  // one per joint
  double rate = 0;                // Hz of sim time; 0: every control step
  int64_t count = 0;              // 0: unlimited
  double duration = 0;            // sim seconds; 0: unlimited
};

struct LaunchPlan {
  std::string file;
  std::string urdf;                  // absolute path
  std::vector<std::string> configs;  // absolute paths; several are merged in order (a later key wins), as rosparam does
  std::string mode = "realtime";     // realtime | lockstep
  bool paused = false;               // sim_server --paused (`paused:`, gazebo_ros's paused arg)
  double physics_rate = 0, control_rate = 0;  // 0: sim_server's defaults
  // CPU for sim_server and controller_manager: "auto" (lockstep: the least busy CPU for both; real time: any),
  // "none", or a CPU number.
  std::string cpu = "auto";
  // Both loop processes' real-time profile (`rt_priority:`, `spin_us:`; launch --rt-priority, --spin-us):
  // rt_priority 0 is the normal scheduler, 1..99 SCHED_FIFO at that priority with memory locked; spin_us is how
  // long each spins before its real-time deadline, -1 meaning kRealTimeSpinUs with rt_priority and 0 without
  // (spinning pays at SCHED_FIFO, where handing the CPU to the other loop costs nothing: bench/README.md).
  int rt_priority = 0;
  int spin_us = -1;
  bool sim = true, controller_manager = true;
  std::vector<std::string> sim_args, cm_args;  // extra flags
  std::vector<std::string> controllers;        // spawned in one strict switch (`controllers:` or `spawn:`)
  std::vector<std::string> inactive;           // loaded, not started (`inactive:`; ROS 2's spawner --inactive)
  std::vector<std::string> spawner_args;       // e.g. --stopped, --timeout 5
  std::vector<CommandSpec> commands;           // registered after the spawner, in order
  bool state_publisher = false;
  std::string sim_name = "sim_server", cm_name = "controller_manager", spawner_name = "spawner",
              state_publisher_name = "state_publisher";
  std::vector<ProcessSpec> processes;  // extra processes
  std::vector<std::string> notes;      // what was mapped or ignored, one line each
  // Robot namespace (`namespace:`, or the spawner's / its group's ns); "": launch --namespace, else the URDF's
  // gazebo_ros_control <robotNamespace>.
  std::string ns;
  // Several copies of the robot (`robots:`), one per namespace, each with its hardware loop on its own URL; empty:
  // one robot.
  std::vector<std::string> robots;
  std::string hardware_lcm_url;  // `hardware_url:` (or `hardware_lcm_url:`; hardware_url_for); "": the shared bus
  double hardware_mirror_hz = 0;  // `hardware_mirror:` with a shm hardware URL: the loop also on the bus, per second
  std::vector<std::pair<std::string, std::string>> args;         // $(arg) values for the YAML (`args:`, <arg>)
  std::vector<std::pair<std::string, std::string>> xacro_args;   // a .xacro urdf's arguments (`xacro_args:`, xacro command=)
  std::vector<std::pair<std::string, double>> initial_positions;  // `initial_positions:`, spawn_model's -J
  // How the root link is mounted (`base:`, launch --fixed-base / --floating-base): "fixed", "floating", or "" for
  // sim_server's default, Gazebo's rule (free unless the URDF welds it to `world`); and where it starts (`base_pose:`,
  // spawn_model's -x -y -z -Y: m, rad) as sim_server's --base-pose.
  std::string base;
  std::optional<std::array<double, 4>> base_pose;
  // <ros2_control> blocks simulated whatever their plugin (`simulate_hardware:`, launch --simulate-hardware).
  std::vector<std::string> simulate_hardware;
};

inline constexpr int kRealTimeSpinUs = 150;
// The spin both loop processes get in real time: spin_us, or its default for rt_priority.
inline int effective_spin_us(const LaunchPlan& p) {
  return p.spin_us >= 0 ? p.spin_us : p.rt_priority > 0 ? kRealTimeSpinUs : 0;
}

// "r0" .. "r{n-1}": the namespaces of `robots: n` and `launch --robots n`.
inline constexpr int kMaxRobots = 64;
std::vector<std::string> robot_names(int n);

// "" if `cpu` is auto, none or a CPU number; else what is wrong with it.
std::string check_cpu(const std::string& cpu);

// The bounds of rt_priority and spin_us, as the loop processes take them.
inline constexpr int kMaxRtPriority = 99, kMaxSpinUs = 100000;

}  // namespace lcm_control::tools
