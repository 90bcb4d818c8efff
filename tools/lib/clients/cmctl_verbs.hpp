// cmctl's verbs as one table (name, aliases, help, arguments, handler): the subcommands, their help, the shell
// completion and the dispatch all come from it.
#pragma once

#include <CLI/CLI.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "bus/bus.hpp"

namespace lcm_control::tools {

// What the verbs' arguments parse into.
struct CmctlArgs {
  double timeout = 3;
  std::vector<std::string> names, start, stop, initial;
  bool best_effort = false, force = false, verbose = false, dot = false;
  std::string state_name, wanted_state, load_state, component_name, component_state, fail_reason, wrench_link;
  std::array<double, 3> wrench_force{0, 0, 0}, wrench_torque{0, 0, 0};
  double wrench_duration = -1;
  int64_t steps = 0;
};

struct CmctlVerb {
  const char* name;
  std::vector<std::string> aliases;
  const char* help;
  void (*arguments)(CLI::App& verb, CmctlArgs& a);  // nullptr: none
  void (*run)(Bus& bus, const CmctlArgs& a);         // prints the answer; throws a refusal's reason
};

const std::vector<CmctlVerb>& cmctl_verbs();

// One subcommand per verb, in the table's order.
void add_cmctl_verbs(CLI::App& app, CmctlArgs& a);

// Runs the verb the command line named (one is required).
int run_cmctl(const CLI::App& app, const CmctlArgs& a, Bus& bus);

}  // namespace lcm_control::tools
