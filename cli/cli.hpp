// What every program's main() shares: the --lcm-url/--namespace/--package-path/--config
// flags (the robot processes' whole common block), and one clear line (no exception trace) plus a non-zero exit on
// failure.
#pragma once

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "description/robot_model.hpp"
#include "description/substitution.hpp"
#include "description/text.hpp"
#include "rt/scheduling.hpp"

namespace lcm_control {

// The environment variable every program's --namespace defaults to (the flag wins), as ROS_NAMESPACE.
inline constexpr const char* kNamespaceEnv = "LCM_CONTROL_NAMESPACE";

struct BusFlags {
  std::string lcm_url;  // "" = LCM_DEFAULT_URL
  std::string ns;
  std::string hardware_lcm_url;  // "" = lcm_url; "auto" or a URL (hardware_url_for)
  std::string hardware_reader = "direct";  // hardware_reader_named()
  double hardware_mirror_hz = 0;  // shared memory: the hardware loop's messages also on the bus, per second
};

inline void add_bus_flags(CLI::App& app, BusFlags& f) {
  app.add_option("--lcm-url", f.lcm_url, "LCM URL (default: $LCM_DEFAULT_URL, else LCM's default)");
  app.add_option("--namespace", f.ns,
                 "prefix every channel with NS/ (one robot per namespace; default: $LCM_CONTROL_NAMESPACE, as "
                 "ROS_NAMESPACE)")
      ->envname(kNamespaceEnv);
}

// For the programs on the hardware loop (sim_server, controller_manager, launch, turret-cmd --sim-time).
inline void add_hardware_url_flag(CLI::App& app, BusFlags& f) {
  app.add_option("--hardware-url,--hardware-lcm-url", f.hardware_lcm_url,
                 "where this robot's hardware loop (hardware/state, hardware/command) travels when not on the "
                 "--lcm-url: `shm` is shared memory on this host (a segment per namespace; `shm:NAME` names it), "
                 "the fastest loop for sim_server and controller_manager on one machine; `auto` moves it to a port of "
                 "the shared group picked by the namespace, so that N robots on one bus cost each process O(1); or "
                 "an LCM URL (default: the --lcm-url)");
}

// For the two loop processes: the shared-memory loop's messages copied to the shared bus for lcm-spy, bus, the
// dashboard and the logger.
inline void add_hardware_mirror_flag(CLI::App& app, BusFlags& f) {
  app.add_option("--hardware-mirror", f.hardware_mirror_hz,
                 "with --hardware-url shm: also publish what this process sends on the hardware loop on the --lcm-url, "
                 "at most HZ times a second of wall time per channel, for lcm-spy, bus, the dashboard and lcm-logger "
                 "(default 0: not at all)")
      ->check(CLI::NonNegativeNumber);
}

// For the two loop processes (sim_server, controller_manager).
inline void add_hardware_reader_flag(CLI::App& app, BusFlags& f) {
  app.add_option("--hardware-reader", f.hardware_reader,
                 "how this process receives on udpm:// URLs: `direct` reads LCM's datagrams on the loop's own "
                 "thread (the hardware loop and the shared bus: no receive thread, a faster hand-off, the order sent "
                 "kept on one URL, nothing kept for good per channel name); `lcm` through LCM's receive thread, which "
                 "keeps every channel name it ever received (default: direct)")
      ->check(CLI::IsMember({"direct", "lcm"}));
}

// ", hardware loop on URL", ", read directly" or "" for a program's ready line.
inline std::string hardware_note(Bus& bus) {
  std::string note = bus.hardware_apart() ? ", hardware loop on " + bus.hardware_url() : "";
  if (ShmLink* shm = bus.hardware_shm()) note += " (" + shm->path() + ")";
  return note + (bus.hardware_socket() ? ", hardware read directly" : "");
}

inline void add_package_path_flag(CLI::App& app, std::vector<std::string>& dirs) {
  app.add_option("--package-path", dirs,
                 "folders searched for package://NAME/ and $(find NAME) (default: $LCM_CONTROL_PACKAGE_PATH, "
                 "$ROS_PACKAGE_PATH)")
      ->delimiter(':');
}

// --config FILE (repeatable): controller YAML files, merged in order by load_robot_model as rosparam loads several
// files into one namespace (a later key wins).
inline CLI::Option* add_config_flag(CLI::App& app, std::vector<std::string>& files, const std::string& what) {
  return app.add_option("--config", files,
                        what + "; repeatable: several files are merged in order, a later file's key winning (maps "
                               "merge key by key), as rosparam loads them");
}

// "" if `v` is NAME=VALUE or NAME:=VALUE, else what is wrong with it (a CLI11 check).
inline std::string check_assignment(const std::string& v) {
  try {
    parse_arg(v);
    return std::string();
  } catch (const std::invalid_argument& e) {
    return std::string(e.what());
  }
}

// --arg NAME=VALUE (repeatable): values for $(arg NAME) in the ros_control YAML.
inline void add_arg_flag(CLI::App& app, std::vector<std::string>& assignments) {
  app.add_option("--arg", assignments,
                 "NAME=VALUE for $(arg NAME) in the YAML, as roslaunch's <rosparam subst_value=\"true\"> fills it "
                 "(repeatable; NAME:=VALUE works too)")
      ->check(check_assignment);
}

// --xacro-arg NAME:=VALUE (repeatable): the arguments of a .xacro robot file, as `xacro FILE NAME:=VALUE` takes them.
inline void add_xacro_arg_flag(CLI::App& app, std::vector<std::string>& assignments) {
  app.add_option("--xacro-arg", assignments,
                 "NAME:=VALUE for <xacro:arg name=\"NAME\"> when the robot file is a .xacro, expanded by our own "
                 "xacro as `xacro FILE NAME:=VALUE` would (repeatable; NAME=VALUE works too)")
      ->check(check_assignment);
}

// --simulate-hardware NAME (repeatable): a <ros2_control> block simulated whatever hardware its plugin names.
inline void add_simulate_hardware_flag(CLI::App& app, std::vector<std::string>& names) {
  app.add_option("--simulate-hardware", names,
                 "NAME: simulate the <ros2_control name=\"NAME\"> block in Bullet whatever its plugin (a robot's "
                 "driver, a vendor's hardware; repeatable)");
}

// How the robot's files are read, from the flags every program that loads them shares.
inline LoadOptions load_options(const std::vector<std::string>& package_path, const BusFlags& bus,
                                const std::vector<std::string>& arg_assignments,
                                const std::vector<std::string>& xacro_arg_assignments = {},
                                const std::vector<std::string>& simulate_hardware = {}) {
  LoadOptions o;
  o.package_path = package_path;
  o.ns = bus.ns;
  for (const auto& a : arg_assignments) o.args.push_back(parse_arg(a));
  for (const auto& a : xacro_arg_assignments) o.xacro_args.push_back(parse_arg(a));
  o.simulate_hardware = simulate_hardware;
  return o;
}

// The robot's files and how they are read (--urdf, --config, --package-path, --arg, --xacro-arg,
// --simulate-hardware): every program that loads a robot takes them alike.
struct RobotFileFlags {
  std::string urdf;
  std::vector<std::string> config, package_path, args, xacro_args, simulate_hardware;
};

inline void add_robot_file_flags(CLI::App& app, RobotFileFlags& f, const std::string& urdf_help,
                                 const std::string& config_help) {
  app.add_option("--urdf", f.urdf, urdf_help)->required();
  add_config_flag(app, f.config, config_help);
  add_package_path_flag(app, f.package_path);
  add_arg_flag(app, f.args);
  add_xacro_arg_flag(app, f.xacro_args);
  add_simulate_hardware_flag(app, f.simulate_hardware);
}

inline LoadOptions load_options(const RobotFileFlags& f, const BusFlags& bus) {
  return load_options(f.package_path, bus, f.args, f.xacro_args, f.simulate_hardware);
}

// The two robot processes' (sim_server, controller_manager) common block: the robot's files, the bus and the hardware
// loop, scheduling, the log level.
struct RobotProcessFlags {
  RobotFileFlags files;
  BusFlags bus;
  SchedulingFlags sched;
  std::string log_level;
};

inline void add_robot_process_flags(CLI::App& app, RobotProcessFlags& f, const std::string& urdf_help,
                                    const std::string& config_help) {
  add_robot_file_flags(app, f.files, urdf_help, config_help);
  add_bus_flags(app, f.bus);
  add_hardware_url_flag(app, f.bus);
  add_hardware_reader_flag(app, f.bus);
  add_hardware_mirror_flag(app, f.bus);
  add_scheduling_flags(app, f.sched);
  app.add_option("--log-level", f.log_level, "debug, info, warn or error");
}

enum ExitCode { kExitOk = 0, kExitFailure = 1, kExitUsage = 2, kExitBadInput = 3, kExitBus = 4 };

// For a program with subcommands whose command line names none: the first word that is neither a flag nor a flag's
// value, when it is not a subcommand ("cmctl lst"), as "'lst' is not a command of cmctl; nearest: list, load; the
// commands: ..."; "" when there is no such word.
inline std::string unknown_subcommand(const CLI::App& app, int argc, char** argv) {
  std::vector<std::string> names, aliases;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    names.push_back(sub->get_name());
    aliases.insert(aliases.end(), sub->get_aliases().begin(), sub->get_aliases().end());
  }
  if (names.empty()) return "";
  aliases.insert(aliases.begin(), names.begin(), names.end());
  for (int k = 1; k < argc; ++k) {
    const std::string word = argv[k];
    if (word == "--") return "";
    if (word.size() > 1 && word[0] == '-') {
      const CLI::Option* o = app.get_option_no_throw(word.substr(0, word.find('=')));
      if (o && o->get_expected_min() > 0 && word.find('=') == std::string::npos) ++k;  // its value
      continue;
    }
    if (std::find(aliases.begin(), aliases.end(), word) != aliases.end()) return "";
    const std::vector<std::string> near = closest_names(word, aliases, 3, std::max<size_t>(2, word.size() / 2));
    return fmt::format("'{}' is not a command of {}; {}the commands: {}", word, app.get_name(),
                       near.empty() ? "" : "nearest: " + join(near) + "; ", join(names));
  }
  return "";
}

// The command line the program was started with, as run_program() kept it (empty before): what a run records of itself
// (run_config_t::argv) so that it can be run again as it was.
inline std::vector<std::string>& command_line_kept() {
  static std::vector<std::string> kept;
  return kept;
}
inline const std::vector<std::string>& command_line() { return command_line_kept(); }

// Parses flags and runs body(); every error becomes "<program>: error: ..." lines on stderr.
template <class Body>
int run_program(CLI::App& app, int argc, char** argv, Body&& body) {
  const std::string program = app.get_name();
  command_line_kept().assign(argv, argv + argc);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (const std::string word = e.get_exit_code() == 0 ? "" : unknown_subcommand(app, argc, argv); !word.empty()) {
      std::fprintf(stderr, "%s: error: %s\nRun with --help for more information.\n", program.c_str(), word.c_str());
      return kExitUsage;
    }
    return app.exit(e) == 0 ? kExitOk : kExitUsage;  // --help is a ParseError that exits 0
  }
  try {
    return body();
  } catch (const ModelError& e) {
    for (const auto& p : e.problems()) std::fprintf(stderr, "%s: error: %s\n", program.c_str(), p.c_str());
    return kExitBadInput;
  } catch (const BusError& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitBus;
  } catch (const CLI::ValidationError& e) {  // an argument found wrong after parsing
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", program.c_str(), e.what());
    return kExitFailure;
  }
}

}  // namespace lcm_control
