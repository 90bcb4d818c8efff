// The launch program's work: read a launch file, start sim_server, controller_manager, the spawner and the file's
// other processes under one Supervisor, wait until they answer, and stop them in order (tools/launch.cpp parses the
// flags into LaunchOptions and calls run_launch).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "tools/lib/launch/launch_plan.hpp"

namespace lcm_control::tools {

// launch's flags; empty strings and negative numbers leave the file's value.
struct LaunchOptions {
  std::string file;  // YAML or ROS launch XML; "": the plan comes from --urdf and --config (plan_from_flags)
  std::string urdf;                  // --urdf, without a FILE
  std::vector<std::string> configs;  // --config, with --urdf
  std::vector<std::string> args;     // --arg NAME=VALUE: $(arg NAME) in the YAML, after the file's
  std::string mode, cpu;
  std::vector<std::string> package_path;
  std::vector<std::string> xacro_args;  // NAME:=VALUE, after the file's
  double ready_timeout = 20, stop_timeout = 5, duration = 0;
  bool dry_run = false, paused = false;
  std::string base;  // --fixed-base: "fixed", --floating-base: "floating"; "": the file's, else sim_server's rule
  bool physics = false;  // --physics: sim_server simulates in Bullet a description that names mock hardware
  std::vector<std::string> simulate_hardware;  // --simulate-hardware NAME, after the file's simulate_hardware:
  int rt_priority = -1, spin_us = -1;
  int robots = 0;  // --robots N; 0: the file's `robots:`
  // --controllers, --inactive: which controllers start and which are only loaded (ROS 2 decides it in the launch
  // file's spawner calls); empty: the file's.
  std::vector<std::string> controllers, inactive;
  bool dashboard = false;
  int dashboard_port = 8080;
  BusFlags bus;
  std::set<std::string> embedding_keys;  // a YAML file that embeds a launch (a scenario): its own keys, left to it
};

// The plan a launch file with only urdf: and config: makes, from --urdf and --config: sim_server and
// controller_manager (run_launch adds a spawner of every controller the YAML configures unless --controllers names
// some). Throws CLI::ValidationError when FILE and --urdf are both given, or neither.
LaunchPlan plan_from_flags(const LaunchOptions& o);

// launch's command line: FILE (then NAME:=VALUE) and the flags, into LaunchOptions.
struct LaunchCommand {
  LaunchOptions options;
  std::vector<std::string> positional;
  bool fixed_base = false, floating_base = false;
};
void add_launch_flags(CLI::App& app, LaunchCommand& c);
int run_launch_command(LaunchCommand c);

// FILE, then NAME:=VALUE for its <arg>s (roslaunch's command line), into o.file and o.args.
void take_launch_arguments(LaunchOptions& o, const std::vector<std::string>& positional);

// The plan launch runs: the launch file (or --urdf and --config) with launch's flags over it and what the robot's
// files decide (the gz plugin's YAML, which controllers start), its notes said on the way. What run_launch starts and
// doctor FILE checks.
LaunchPlan resolve_launch(const LaunchOptions& o);

// Runs the launch to its end; returns the exit code, throws as run_program expects (CLI::ValidationError for a
// usage error, ModelError for a bad file, runtime_error when a process failed).
int run_launch(const LaunchOptions& o);

// Several robots (`robots:`, --robots): one launch of the file per robot namespace, supervised as one.
int run_robots(const LaunchOptions& o, const LaunchPlan& plan);

// The command line of each process launch starts for one robot, its namespace not yet given (with_ns).
struct CommandLines {
  std::vector<std::string> sim, cm, spawner, rsp, dash;
};
CommandLines command_lines(const LaunchPlan& plan, const LaunchOptions& o, const std::string& hw_url, bool hw_apart);
std::vector<std::string> with_ns(std::vector<std::string> argv, const std::string& ns);

// One line of launch's own on stdout, prefixed "[launch] ".
void launch_say(const std::string& line);

}  // namespace lcm_control::tools
