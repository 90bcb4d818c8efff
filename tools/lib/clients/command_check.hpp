// What every publishing tool (turret-cmd, send-trajectory, gripper, drive, `bus pub`) checks before it commands a
// controller, from the controller manager's list: the controller is loaded, its command channel takes the type the
// tool sends, and (for goals) it runs; and what a failed goal owes to the hardware (e-stop, a paused or silent
// simulator), from the same list's hardware line.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "bus/bus.hpp"
#include "lcm_control/cm_response_t.hpp"
#include "lcm_control/controller_info_t.hpp"

namespace lcm_control::tools {

// The command line that commands what `c` takes ("send-trajectory arm_controller ...", "turret-cmd j1 VALUE",
// "drive base LINEAR ANGULAR", `bus pub` for another type); "" when it takes nothing.
std::string commanded_with(const controller_info_t& c);

// What a tool sends on a controller's channel: the type's name ("float64_t") and, for float64_array_t, how many
// numbers (0: not counted).
struct Sent {
  std::string type;
  int width = 0;
};

// "" when `c` takes `sent` on `channel` (its name relative to the controller, e.g. "command"); else the refusal
// naming both types and what to use, e.g. "trajectory_controller takes joint_trajectory_t on
// trajectory_controller/command; float64_t was given: use send-trajectory trajectory_controller ...". `prefix` is
// the namespace prefix of the channel names shown (Bus::channel("")).
std::string type_mismatch(const controller_info_t& c, const Sent& sent, const std::string& channel,
                          const std::string& prefix = "");

// `name` among the controllers the manager lists, if it takes `sent` on its command channel and runs; else
// std::runtime_error (exit 1) saying what to do: spawner (with `load_hint` after it, and the closest name), the
// right tool, cmctl start.
const controller_info_t& commandable(const std::vector<controller_info_t>& listed, const std::string& name,
                                     const Sent& sent, const std::string& load_hint = "",
                                     const std::string& prefix = "");

// The controller whose command channel `channel` (without the namespace) is, among those listed; nullptr for none.
// `relative` receives the channel's part after "<name>/".
const controller_info_t* controller_on(const std::vector<controller_info_t>& listed, const std::string& channel,
                                       std::string* relative = nullptr);

// A channel as a ROS 2 user writes it, as ours: a leading '/' dropped (channels are relative to --namespace), and a
// ROS 2 controller topic (`<c>/commands`, `<c>/joint_trajectory`) is the command channel of controller <c> as
// `listed` shows it (without a list: `<c>/command`); `note` gets a line saying so ("" when `name` is ours already).
// Throws std::runtime_error (exit 1) with the tool to use for a private name (`~/...`) and for an action
// (`<c>/follow_joint_trajectory`, `<c>/gripper_cmd`).
std::string channel_from_ros(const std::string& name, const std::vector<controller_info_t>* listed, std::string* note);

// For `bus pub` and drive on CHANNEL (without the namespace): when the controller manager answers within timeout_s
// and lists a controller whose command channel CHANNEL is, throws std::runtime_error (exit 1) if it takes another
// type than `sent`; when it lists none, warns on stderr naming the command channels there are (nothing listens).
// Silent when no manager answers; only a channel ending in /command, /cmd_vel or /reference is asked about.
void check_command_channel(Bus& bus, const std::string& channel, const Sent& sent, double timeout_s);
// The same with the manager's LIST answer already at hand (nullptr: none came).
void check_command_channel(Bus& bus, const std::string& channel, const Sent& sent, const cm_response_t* listed);
// The manager's LIST answer within timeout_s, or nullopt.
std::optional<cm_response_t> try_list(Bus& bus, const char* client, double timeout_s);

// The channel (relative to the controller) `controller` takes its twist_t on, as the controller manager lists it
// within timeout_s: cmd_vel (diff drive, tricycle, omni) or reference (ROS 2's steering and mecanum drives);
// cmd_vel when no manager answers or it lists no such controller.
std::string twist_channel(Bus& bus, const std::string& controller, double timeout_s);

// Why the hardware may have made a goal fail, from a LIST answer's hardware line: "the e-stop is engaged (...)",
// "the simulator is paused (...)", "the hardware is silent (...)"; nullopt when it says none of these.
std::optional<std::string> hardware_cause(const cm_response_t& list);

class CmClient;
// A goal's failure line "CONTROLLER: STATUS: MESSAGE", with the hardware's cause when the manager (asked now, for
// 1 s at most) names one: "CONTROLLER: STATUS because the e-stop is engaged: ...; the controller says: MESSAGE".
std::string goal_failure(CmClient& cm, const std::string& controller, const std::string& status,
                         const std::string& message);

}  // namespace lcm_control::tools
