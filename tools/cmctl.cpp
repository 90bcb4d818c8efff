// cmctl: the controller_manager command line (list, list-types, load, unload,
// start, stop, switch, reload, and ROS 2's `ros2 control` verbs beside them)
// over controller_manager/request and /response, and the simulation's (pause,
// resume, step, reset, sim-status) over sim_server/request and /response.
#include <fmt/ranges.h>

#include <optional>

#include "cli/cli.hpp"
#include "description/hardware_components.hpp"
#include "tools/lib/cm_client.hpp"
#include "tools/lib/cm_views.hpp"
#include "tools/lib/sim_client.hpp"
#include "tools/lib/support.hpp"

int main(int argc, char** argv) {
  using namespace lcm_control;
  using namespace lcm_control::tools;
  CLI::App app{
      "Talk to the controller manager (ROS's `rosrun controller_manager controller_manager ...`). Every request waits "
      "at most --timeout for the answer; a refused request prints the manager's reason and exits 1, no answer exits 4.\n"
      "Examples:\n"
      "  cmctl list\n"
      "  cmctl load j1_controller && cmctl start j1_controller\n"
      "  cmctl switch --start j2_effort_controller --stop j2_controller\n"
      "  cmctl --namespace robot1 list-types\n"
      "  cmctl set-controller-state arm_controller active      (ROS 2's words: ros2 control ...)\n"
      "  cmctl switch-controllers --activate vel --deactivate pos\n"
      "  cmctl list-hardware-interfaces\n"
      "  cmctl set-hardware-component-state Arm inactive\n"
      "  cmctl statistics\n"
      "  cmctl pause && cmctl step 100 && cmctl resume\n"
      "  cmctl reset -J j1=0.5",
      "cmctl"};
  BusFlags bus_flags;
  double timeout = 3;
  add_bus_flags(app, bus_flags);
  app.add_option("--timeout", timeout, "seconds to wait for each answer")->check(CLI::PositiveNumber);
  app.require_subcommand(1);
  app.fallthrough();  // `cmctl list --lcm-url URL` as well as `cmctl --lcm-url URL list`
  std::vector<std::string> names, start, stop;
  bool best_effort = false, force = false;
  auto* list = app.add_subcommand("list", "controllers with type, state, joints and interface")->alias("list-controllers");
  bool verbose = false;
  list->add_flag("--verbose", verbose, "every joint of each controller (by default more than three are shown as "
                                          "first..last (count)) and the reference interfaces chainable ones export");
  auto* types = app.add_subcommand("list-types", "controller types this manager can load")->alias("list-controller-types");
  bool type_docs = false;
  types->add_flag("--verbose", type_docs, "each type with what it declares: ROS 1 or ROS 2, chainable, a line of doc");
  auto* interfaces = app.add_subcommand("list-hardware-interfaces",
                                        "each joint's command interfaces (available, claimed by whom) and state ones");
  auto* components = app.add_subcommand("list-hardware-components",
                                        "each hardware component (<ros2_control> block): lifecycle state, type, "
                                        "plugin, joints, the controllers using it");
  auto* set_component = app.add_subcommand(
      "set-hardware-component-state",
      "ROS 2: NAME unconfigured, inactive, active or finalized; leaving active stops the controllers commanding it, "
      "leaving inactive those reading it too");
  auto* fail_component = app.add_subcommand(
      "fail-hardware-component",
      "sim_server's test hook: NAME fails as a lost device would; the controller manager deactivates its controllers");
  std::string component_name, component_state, fail_reason;
  set_component->add_option("NAME", component_name, "hardware component (<ros2_control name=...>)")->required();
  set_component->add_option("STATE", component_state, "unconfigured, inactive, active or finalized")
      ->required()
      ->check(CLI::IsMember({"unconfigured", "inactive", "active", "finalized"}));
  fail_component->add_option("NAME", component_name, "hardware component (<ros2_control name=...>)")->required();
  fail_component->add_option("--reason", fail_reason, "why, as the controller manager will log it");
  auto* wrench = app.add_subcommand(
      "apply-body-wrench",
      "Gazebo's apply_body_wrench: push LINK with a force (and torque), world frame, at its centre of mass, for "
      "--duration s of sim time (a negative one: until cleared; 0 clears)");
  std::string wrench_link;
  std::array<double, 3> wrench_force{0, 0, 0}, wrench_torque{0, 0, 0};
  double wrench_duration = -1;
  wrench->add_option("LINK", wrench_link, "the URDF link to push")->required();
  wrench->add_option("--force", wrench_force, "FX,FY,FZ in N, world frame")->delimiter(',');
  wrench->add_option("--torque", wrench_torque, "TX,TY,TZ in N*m, world frame")->delimiter(',');
  wrench->add_option("--duration", wrench_duration, "seconds of sim time (default -1: until cleared; 0: clear)");
  auto* stats = app.add_subcommand("statistics", "the controller manager's last statistics window: per controller its "
                                                 "updates' execution time and period (mean, p99, max), and sim_server's");
  auto* hw_status = app.add_subcommand("view-hardware-status",
                                       "ROS 2: each hardware component, its state and its interfaces' current values "
                                       "and claimants");
  auto* chains = app.add_subcommand("view-controller-chains",
                                    "ROS 2: controllers, what they command or read, and the hardware components; "
                                    "--dot for Graphviz");
  bool dot = false;
  chains->add_flag("--dot", dot, "print a Graphviz graph (cmctl view-controller-chains --dot | dot -Tpdf -o chains.pdf)");
  auto* load = app.add_subcommand("load", "load (configure) controllers from the YAML")->alias("load-controller");
  auto* unload = app.add_subcommand("unload", "unload stopped controllers")->alias("unload-controller");
  auto* set_state = app.add_subcommand("set-controller-state", "ROS 2: NAME inactive (stop; loads it if needed) or "
                                                               "active (start; loads it if needed)")
                        ->alias("set-state");
  auto* start_cmd = app.add_subcommand("start", "start controllers (one strict switch)");
  auto* stop_cmd = app.add_subcommand("stop", "stop controllers (one strict switch)");
  auto* sw = app.add_subcommand("switch", "stop some and start others in one switch");
  sw->alias("switch-controllers");
  auto* reload = app.add_subcommand("reload", "reload_controller_libraries: unload all and re-read the config")
                     ->alias("reload-controller-libraries");
  auto* pause = app.add_subcommand("pause", "sim_server: hold sim time (Gazebo's pause_physics); switching still works");
  auto* resume = app.add_subcommand("resume", "sim_server: run again from where it paused");
  auto* step_cmd = app.add_subcommand("step", "sim_server, paused: advance exactly N control steps, then pause again");
  auto* reset = app.add_subcommand(
      "reset", "sim_server: every joint back to the start pose, sim time to 0; running controllers restart from there");
  auto* sim_status = app.add_subcommand("sim-status", "sim_server: running or paused, step, sim time, resets");
  int64_t steps = 0;
  step_cmd->add_option("N", steps, "control steps (>= 1)")->required()->check([](const std::string& v) {
    return v.find_first_not_of("0123456789") == std::string::npos && v.find_first_not_of('0') != std::string::npos
               ? std::string()
               : "N must be a whole number of control steps >= 1, not '" + v + "'";
  });
  std::vector<std::string> initial;
  reset->add_option("-J,--initial-position", initial,
                    "JOINT=VALUE: a new start position for that joint (rad or m; repeatable), kept for later resets; "
                    "other joints go back to sim_server's -J (or 0)")
      ->check(initial_position_problem);
  for (auto* sc : {load, unload, start_cmd, stop_cmd}) sc->add_option("NAME", names, "controller names")->required();
  std::string load_state, wanted_state, state_name;
  load->add_option("--set-state", load_state, "ROS 2: then make it inactive (loaded) or active (started)")
      ->check(CLI::IsMember({"inactive", "active"}));
  set_state->add_option("NAME", state_name, "controller name")->required();
  set_state->add_option("STATE", wanted_state, "inactive or active")
      ->required()
      ->check(CLI::IsMember({"inactive", "active"}));
  sw->add_option("--start,--activate", start, "controllers to start (ROS 2: activate)");
  sw->add_option("--stop,--deactivate", stop, "controllers to stop (ROS 2: deactivate)");
  sw->add_flag("--best-effort", best_effort, "start/stop what can be, skip what cannot (default: strict, all or none)");
  sw->add_flag("--strict", "all or none (the default; ROS 2's flag, accepted)");
  reload->add_flag("--force,--force-kill", force, "stop and unload running controllers first");
  return run_program(app, argc, argv, [&] {
    install_stop_signals();
    Bus bus(bus_flags.lcm_url, bus_flags.ns);  // LCM's receive thread: a short-lived tool waiting for answers
    for (auto* sc : {pause, resume, step_cmd, reset, sim_status, fail_component, wrench}) {
      if (!sc->parsed()) continue;
      SimClient sim(bus, "cmctl");
      sim_response_t a;
      if (wrench->parsed()) a = sim.apply_wrench(wrench_link, wrench_force, wrench_torque, wrench_duration, timeout);
      if (fail_component->parsed()) a = sim.fail_component(component_name, fail_reason, timeout);
      if (pause->parsed()) a = sim.pause(timeout);
      if (resume->parsed()) a = sim.resume(timeout);
      if (step_cmd->parsed()) a = sim.step(steps, timeout);
      if (sim_status->parsed()) a = sim.status(timeout);
      if (reset->parsed()) {
        InitialPositions start;
        for (const auto& v : initial) {
          const auto [joint, q] = parse_initial_position(v);
          start[joint] = q;
        }
        a = sim.reset(start, timeout);
      }
      if (!a.ok) throw std::runtime_error(a.message.empty() ? "refused (no reason given)" : a.message);
      fmt::print("{}\n", a.message);
      return int(kExitOk);
    }
    if (stats->parsed()) {
      fmt::print("{}", wait_statistics(bus, std::max(timeout, 2.5)));
      return int(kExitOk);
    }
    CmClient cm(bus, "cmctl");
    cm_response_t r;
    // The state `name` is in ("" when not loaded).
    auto state_of = [&](const std::string& name) {
      const cm_response_t l = cm.list(timeout);
      for (const auto& c : l.controllers)
        if (c.name == name) return c.state;
      return std::string();
    };
    if (list->parsed()) {
      r = cm.list(timeout);
      if (r.ok) {
        fmt::print("{}", r.controllers.empty() ? "no controllers loaded\n" : controller_table(r.controllers, r.ros2, verbose));
        if (r.message.find(" listed, in load order: ") != std::string::npos) fmt::print("{}\n", r.message);
        if (!r.hardware.empty()) fmt::print("hardware: {}\n", r.hardware);
        std::vector<std::string> down;  // said only when one is not active
        for (const auto& c : r.components)
          if (c.state != hardware_command_t::COMPONENT_ACTIVE)
            down.push_back(fmt::format("{} ({}{})", c.name, c.state_label,
                                       c.error.empty() ? "" : " after an error: " + c.error));
        if (!down.empty()) fmt::print("hardware components not active: {}\n", fmt::join(down, ", "));
      }
    } else if (interfaces->parsed()) {
      r = cm.list(timeout);
      if (r.ok) fmt::print("{}", hardware_interfaces_text(r.joints));
    } else if (components->parsed()) {
      r = cm.list(timeout);
      if (r.ok) fmt::print("{}", hardware_components_text(r.components));
    } else if (hw_status->parsed() || chains->parsed()) {
      r = cm.list(timeout);
      if (r.ok)
        fmt::print("{}", hw_status->parsed() ? hardware_status_text(r)
                         : dot               ? controller_chains_dot(r)
                                             : controller_chains_text(r));
    } else if (set_component->parsed()) {
      r = cm.set_component_state(component_name, static_cast<int8_t>(*lifecycle_from(component_state)), timeout);
    } else if (set_state->parsed() || (load->parsed() && !load_state.empty())) {
      const std::string state = set_state->parsed() ? wanted_state : load_state;
      if (set_state->parsed()) names = {state_name};
      for (const auto& name : names) {
        std::string now = state_of(name);
        if (now.empty()) {
          r = cm.load({name}, timeout);
          if (!r.ok) break;
          now = "initialized";
        }
        if ((now == "running") != (state == "active"))
          r = state == "active" ? cm.switch_controllers({name}, {}, true, timeout)
                                : cm.switch_controllers({}, {name}, true, timeout);
        else
          r.ok = true;
        if (!r.ok) break;
        r.message = fmt::format("{} is {}", name, ros2_state(state_of(name)));
      }
    } else if (types->parsed()) {
      r = cm.list_types(timeout);
      if (r.ok)
        for (size_t k = 0; k < r.types.size(); ++k)
          fmt::print("{}{}\n", r.types[k],
                     type_docs && k < r.type_docs.size() && !r.type_docs[k].empty() ? "  " + r.type_docs[k] : "");
    } else if (load->parsed()) {
      r = cm.load(names, timeout);
    } else if (unload->parsed()) {
      r = cm.unload(names, timeout);
    } else if (start_cmd->parsed()) {
      r = cm.switch_controllers(names, {}, true, timeout);
    } else if (stop_cmd->parsed()) {
      r = cm.switch_controllers({}, names, true, timeout);
    } else if (sw->parsed()) {
      if (start.empty() && stop.empty()) throw std::runtime_error("switch needs --start and/or --stop");
      r = cm.switch_controllers(start, stop, !best_effort, timeout);
    } else if (reload->parsed()) {
      r = cm.reload(force, timeout);
    }
    if (!r.ok) throw std::runtime_error(r.message.empty() ? "refused (no reason given)" : r.message);
    const bool printed = list->parsed() || types->parsed() || interfaces->parsed() || components->parsed() ||
                         hw_status->parsed() || chains->parsed();
    if (!printed) fmt::print("{}\n", r.message.empty() ? "ok" : r.message);
    return int(kExitOk);
  });
}
