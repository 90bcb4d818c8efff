// The spawner program: its flags, and the run (spawn the controllers, stay until Ctrl-C or SIGTERM, then stop and
// unload them). tools/spawner.cpp parses the flags and calls run_spawner.
#pragma once

#include <string>
#include <vector>

#include "cli/cli.hpp"
#include "tools/lib/launch/spawn.hpp"

namespace lcm_control::tools {

struct SpawnerFlags {
  std::vector<std::string> names;
  SpawnOptions o;
  double shutdown_timeout = 1.5;
  bool hardware_later = false;
  BusFlags bus;
  std::string manager, param_file;  // ROS 2's -c and -p
};

void add_spawner_flags(CLI::App& app, SpawnerFlags& f);

// Exit 0, or 1 when a controller could not be spawned (each named with its reason).
int run_spawner(SpawnerFlags f);

}  // namespace lcm_control::tools
