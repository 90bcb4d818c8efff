// What every program's main() shares: the --lcm-url/--namespace/--package-path
// flags, and one clear line (no exception trace) plus a non-zero exit on failure.
#pragma once

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "common/bus.hpp"
#include "common/robot_model.hpp"

namespace lcm_control {

struct BusFlags {
  std::string lcm_url;  // "" = LCM_DEFAULT_URL
  std::string ns;
};

inline void add_bus_flags(CLI::App& app, BusFlags& f) {
  app.add_option("--lcm-url", f.lcm_url, "LCM URL (default: $LCM_DEFAULT_URL, else LCM's default)");
  app.add_option("--namespace", f.ns, "prefix every channel with NS/ (one robot per namespace)");
}

inline void add_package_path_flag(CLI::App& app, std::vector<std::string>& dirs) {
  app.add_option("--package-path", dirs,
                 "folders searched for package://NAME/ and $(find NAME) (default: $LCM_CONTROL_PACKAGE_PATH, "
                 "$ROS_PACKAGE_PATH)")
      ->delimiter(':');
}

enum ExitCode { kExitOk = 0, kExitFailure = 1, kExitUsage = 2, kExitBadInput = 3, kExitBus = 4 };

// Parses flags and runs body(); every error becomes "<program>: error: ..." lines on stderr.
template <class Body>
int run_program(CLI::App& app, int argc, char** argv, Body&& body) {
  const std::string program = app.get_name();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  try {
    return body();
  } catch (const ModelError& e) {
    for (const auto& p : e.problems()) std::fprintf(stderr, "%s: error: %s\n", program.c_str(), p.c_str());
    return kExitBadInput;
  } catch (const BusError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitBus;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitFailure;
  }
}

}  // namespace lcm_control
