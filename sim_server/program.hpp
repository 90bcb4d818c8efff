// sim_server as a program: its flags, the plan they make with the robot's files (rates, base, hardware, brakes: pure,
// tested), and the run that wires the simulation to the bus. main() parses the flags and calls run_sim_server.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "description/robot_model.hpp"
#include "sim_server/multibody_builder.hpp"
#include "sim_server/simulation.hpp"
#include "sim_server/stepper.hpp"

namespace lcm_control::sim {

struct ProgramFlags {
  RobotProcessFlags robot;
  std::optional<double> physics_hz, control_hz;  // unset: from the YAML's update_rate, else 1000 Hz
  double clock_hz = 100;
  std::string mode = "realtime", overrun = "catch-up";
  StepperOptions stepper;
  long timer_slack_ns = 50000;
  std::vector<std::string> initial;  // -J JOINT=VALUE
  bool floating = false, fixed = false, ground = false, no_ground = false, no_brakes = false;
  std::vector<double> base_pose;  // X Y Z YAW
  std::optional<double> x, y, z, yaw;
  bool mock_hardware = false, physics = false;
};

void add_program_flags(CLI::App& app, ProgramFlags& f);

// What the flags and the robot's files decide before anything runs.
struct RunPlan {
  SimulationRates rates;
  int clock_every = 1;          // control steps per `clock` message
  WorldOptions world;
  InitialPositions start;       // <ros2_control> initial_value, then -J
  bool mock = false;            // no physics: mock hardware
  bool brakes = true;           // joints nobody commands are braked where they are
  std::vector<std::string> notes;  // what the plan took from the files, for the log
};

// Throws std::invalid_argument for rates that do not divide, CLI::ValidationError for flags that contradict the files.
RunPlan plan_run(const ProgramFlags& f, const RobotModel& model);

int run_sim_server(ProgramFlags f);

}  // namespace lcm_control::sim
