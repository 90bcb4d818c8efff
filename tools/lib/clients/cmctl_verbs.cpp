#include "tools/lib/clients/cmctl_verbs.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <stdexcept>

#include "cli/cli.hpp"
#include "description/hardware_components.hpp"
#include "description/initial_positions.hpp"
#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/cm_views.hpp"
#include "tools/lib/clients/sim_client.hpp"

namespace lcm_control::tools {
namespace {

template <class Response>
Response granted(Response r) {
  if (!r.ok) throw std::runtime_error(r.message.empty() ? "refused (no reason given)" : r.message);
  return r;
}

// A request that changes something: its answer, or "ok".
void said(const cm_response_t& r) { fmt::print("{}\n", granted(r).message.empty() ? "ok" : r.message); }
void said(const sim_response_t& a) { fmt::print("{}\n", granted(a).message); }

void names(CLI::App& v, CmctlArgs& a) { v.add_option("NAME", a.names, "controller names")->required(); }

cm_response_t listed(Bus& bus, const CmctlArgs& a) { return granted(CmClient(bus, "cmctl").list(a.timeout)); }

void list(Bus& bus, const CmctlArgs& a) {
  const cm_response_t r = listed(bus, a);
  fmt::print("{}", r.controllers.empty() ? "no controllers loaded\n" : controller_table(r.controllers, r.ros2, a.verbose));
  if (r.message.find(" listed, in load order: ") != std::string::npos) fmt::print("{}\n", r.message);
  if (!r.hardware.empty()) fmt::print("hardware: {}\n", r.hardware);
  std::vector<std::string> down;  // said only when one is not active
  for (const auto& c : r.components)
    if (c.state != hardware_command_t::COMPONENT_ACTIVE)
      down.push_back(fmt::format("{} ({}{})", c.name, c.state_label, c.error.empty() ? "" : " after an error: " + c.error));
  if (!down.empty()) fmt::print("hardware components not active: {}\n", fmt::join(down, ", "));
}

void list_types(Bus& bus, const CmctlArgs& a) {
  const cm_response_t r = granted(CmClient(bus, "cmctl").list_types(a.timeout));
  for (size_t k = 0; k < r.types.size(); ++k)
    fmt::print("{}{}\n", r.types[k],
               a.verbose && k < r.type_docs.size() && !r.type_docs[k].empty() ? "  " + r.type_docs[k] : "");
}

// ROS 2's set_controller_state: each controller loaded if need be, then switched to `state` (inactive or active).
void set_states(Bus& bus, const CmctlArgs& a, const std::vector<std::string>& controllers, const std::string& state) {
  CmClient cm(bus, "cmctl");
  auto state_of = [&](const std::string& name) {  // "" when not loaded
    for (const auto& c : granted(cm.list(a.timeout)).controllers)
      if (c.name == name) return c.state;
    return std::string();
  };
  cm_response_t r;
  for (const auto& name : controllers) {
    std::string now = state_of(name);
    if (now.empty()) {
      granted(cm.load({name}, a.timeout));
      now = "initialized";
    }
    if ((now == "running") != (state == "active"))
      granted(state == "active" ? cm.switch_controllers({name}, {}, true, a.timeout)
                                : cm.switch_controllers({}, {name}, true, a.timeout));
    r.message = fmt::format("{} is {}", name, ros2_state(state_of(name)));
  }
  fmt::print("{}\n", r.message);
}

const std::vector<CmctlVerb> kVerbs = {
    {"list", {"list-controllers"}, "controllers with type, state, joints and interface",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_flag("--verbose", a.verbose,
                  "every joint of each controller (by default more than three are shown as first..last (count)) and "
                  "the reference interfaces chainable ones export");
     },
     list},
    {"list-types", {"list-controller-types"}, "controller types this manager can load",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_flag("--verbose", a.verbose, "each type with what it declares: ROS 1 or ROS 2, chainable, a line of doc");
     },
     list_types},
    {"list-hardware-interfaces", {}, "each joint's command interfaces (available, claimed by whom) and state ones",
     nullptr, [](Bus& bus, const CmctlArgs& a) { fmt::print("{}", hardware_interfaces_text(listed(bus, a).joints)); }},
    {"list-hardware-components", {},
     "each hardware component (<ros2_control> block): lifecycle state, type, plugin, joints, the controllers using it",
     nullptr,
     [](Bus& bus, const CmctlArgs& a) { fmt::print("{}", hardware_components_text(listed(bus, a).components)); }},
    {"set-hardware-component-state", {},
     "ROS 2: NAME unconfigured, inactive, active or finalized; leaving active stops the controllers commanding it, "
     "leaving inactive those reading it too",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("NAME", a.component_name, "hardware component (<ros2_control name=...>)")->required();
       v.add_option("STATE", a.component_state, "unconfigured, inactive, active or finalized")
           ->required()
           ->check(CLI::IsMember({"unconfigured", "inactive", "active", "finalized"}));
     },
     [](Bus& bus, const CmctlArgs& a) {
       said(CmClient(bus, "cmctl")
                .set_component_state(a.component_name, static_cast<int8_t>(*lifecycle_from(a.component_state)),
                                     a.timeout));
     }},
    {"fail-hardware-component", {},
     "sim_server's test hook: NAME fails as a lost device would; the controller manager deactivates its controllers",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("NAME", a.component_name, "hardware component (<ros2_control name=...>)")->required();
       v.add_option("--reason", a.fail_reason, "why, as the controller manager will log it");
     },
     [](Bus& bus, const CmctlArgs& a) {
       said(SimClient(bus, "cmctl").fail_component(a.component_name, a.fail_reason, a.timeout));
     }},
    {"apply-body-wrench", {},
     "Gazebo's apply_body_wrench: push LINK with a force (and torque), world frame, at its centre of mass, for "
     "--duration s of sim time (a negative one: until cleared; 0 clears)",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("LINK", a.wrench_link, "the URDF link to push")->required();
       v.add_option("--force", a.wrench_force, "FX,FY,FZ in N, world frame")->delimiter(',');
       v.add_option("--torque", a.wrench_torque, "TX,TY,TZ in N*m, world frame")->delimiter(',');
       v.add_option("--duration", a.wrench_duration, "seconds of sim time (default -1: until cleared; 0: clear)");
     },
     [](Bus& bus, const CmctlArgs& a) {
       said(SimClient(bus, "cmctl").apply_wrench(a.wrench_link, a.wrench_force, a.wrench_torque, a.wrench_duration,
                                                 a.timeout));
     }},
    {"statistics", {},
     "the controller manager's last statistics window: per controller its updates' execution time and period (mean, "
     "p99, max), and sim_server's",
     nullptr, [](Bus& bus, const CmctlArgs& a) { fmt::print("{}", wait_statistics(bus, std::max(a.timeout, 2.5))); }},
    {"view-hardware-status", {},
     "ROS 2: each hardware component, its state and its interfaces' current values and claimants", nullptr,
     [](Bus& bus, const CmctlArgs& a) { fmt::print("{}", hardware_status_text(listed(bus, a))); }},
    {"view-controller-chains", {},
     "ROS 2: controllers, what they command or read, and the hardware components; --dot for Graphviz",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_flag("--dot", a.dot, "print a Graphviz graph (cmctl view-controller-chains --dot | dot -Tpdf -o chains.pdf)");
     },
     [](Bus& bus, const CmctlArgs& a) {
       const cm_response_t r = listed(bus, a);
       fmt::print("{}", a.dot ? controller_chains_dot(r) : controller_chains_text(r));
     }},
    {"load", {"load-controller"}, "load (configure) controllers from the YAML",
     [](CLI::App& v, CmctlArgs& a) {
       names(v, a);
       v.add_option("--set-state", a.load_state, "ROS 2: then make it inactive (loaded) or active (started)")
           ->check(CLI::IsMember({"inactive", "active"}));
     },
     [](Bus& bus, const CmctlArgs& a) {
       if (!a.load_state.empty()) return set_states(bus, a, a.names, a.load_state);
       said(CmClient(bus, "cmctl").load(a.names, a.timeout));
     }},
    {"unload", {"unload-controller"}, "unload stopped controllers", names,
     [](Bus& bus, const CmctlArgs& a) { said(CmClient(bus, "cmctl").unload(a.names, a.timeout)); }},
    {"set-controller-state", {"set-state"},
     "ROS 2: NAME inactive (stop; loads it if needed) or active (start; loads it if needed)",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("NAME", a.state_name, "controller name")->required();
       v.add_option("STATE", a.wanted_state, "inactive or active")->required()->check(CLI::IsMember({"inactive", "active"}));
     },
     [](Bus& bus, const CmctlArgs& a) { set_states(bus, a, {a.state_name}, a.wanted_state); }},
    {"start", {}, "start controllers (one strict switch)", names,
     [](Bus& bus, const CmctlArgs& a) {
       said(CmClient(bus, "cmctl").switch_controllers(a.names, {}, true, a.timeout));
     }},
    {"stop", {}, "stop controllers (one strict switch)", names,
     [](Bus& bus, const CmctlArgs& a) {
       said(CmClient(bus, "cmctl").switch_controllers({}, a.names, true, a.timeout));
     }},
    {"switch", {"switch-controllers"}, "stop some and start others in one switch",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("--start,--activate", a.start, "controllers to start (ROS 2: activate)");
       v.add_option("--stop,--deactivate", a.stop, "controllers to stop (ROS 2: deactivate)");
       v.add_flag("--best-effort", a.best_effort,
                  "start/stop what can be, skip what cannot (default: strict, all or none)");
       v.add_flag("--strict", "all or none (the default; ROS 2's flag, accepted)");
     },
     [](Bus& bus, const CmctlArgs& a) {
       if (a.start.empty() && a.stop.empty()) throw std::runtime_error("switch needs --start and/or --stop");
       said(CmClient(bus, "cmctl").switch_controllers(a.start, a.stop, !a.best_effort, a.timeout));
     }},
    {"reload", {"reload-controller-libraries"}, "reload_controller_libraries: unload all and re-read the config",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_flag("--force,--force-kill", a.force, "stop and unload running controllers first");
     },
     [](Bus& bus, const CmctlArgs& a) { said(CmClient(bus, "cmctl").reload(a.force, a.timeout)); }},
    {"pause", {}, "sim_server: hold sim time (Gazebo's pause_physics); switching still works", nullptr,
     [](Bus& bus, const CmctlArgs& a) { said(SimClient(bus, "cmctl").pause(a.timeout)); }},
    {"resume", {}, "sim_server: run again from where it paused", nullptr,
     [](Bus& bus, const CmctlArgs& a) { said(SimClient(bus, "cmctl").resume(a.timeout)); }},
    {"step", {}, "sim_server, paused: advance exactly N control steps, then pause again",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("N", a.steps, "control steps (>= 1)")->required()->check([](const std::string& s) {
         return s.find_first_not_of("0123456789") == std::string::npos && s.find_first_not_of('0') != std::string::npos
                    ? std::string()
                    : "N must be a whole number of control steps >= 1, not '" + s + "'";
       });
     },
     [](Bus& bus, const CmctlArgs& a) { said(SimClient(bus, "cmctl").step(a.steps, a.timeout)); }},
    {"reset", {},
     "sim_server: every joint back to the start pose, sim time to 0; running controllers restart from there",
     [](CLI::App& v, CmctlArgs& a) {
       v.add_option("-J,--initial-position", a.initial,
                    "JOINT=VALUE: a new start position for that joint (rad or m; repeatable), kept for later resets; "
                    "other joints go back to sim_server's -J (or 0)")
           ->check(initial_position_problem);
     },
     [](Bus& bus, const CmctlArgs& a) {
       InitialPositions start;
       for (const auto& v : a.initial) {
         const auto [joint, q] = parse_initial_position(v);
         start[joint] = q;
       }
       said(SimClient(bus, "cmctl").reset(start, a.timeout));
     }},
    {"sim-status", {}, "sim_server: running or paused, step, sim time, resets", nullptr,
     [](Bus& bus, const CmctlArgs& a) { said(SimClient(bus, "cmctl").status(a.timeout)); }},
};

}  // namespace

const std::vector<CmctlVerb>& cmctl_verbs() { return kVerbs; }

void add_cmctl_verbs(CLI::App& app, CmctlArgs& a) {
  app.require_subcommand(1);
  for (const CmctlVerb& verb : kVerbs) {
    CLI::App* v = app.add_subcommand(verb.name, verb.help);
    for (const auto& alias : verb.aliases) v->alias(alias);
    if (verb.arguments) verb.arguments(*v, a);
  }
}

int run_cmctl(const CLI::App& app, const CmctlArgs& a, Bus& bus) {
  for (const CmctlVerb& verb : kVerbs)
    if (app.get_subcommand(verb.name)->parsed()) {
      verb.run(bus, a);
      return kExitOk;
    }
  throw CLI::ValidationError("cmctl", "no command given; run cmctl --help for the list");
}

}  // namespace lcm_control::tools
