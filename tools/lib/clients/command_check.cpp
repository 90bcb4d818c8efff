#include "tools/lib/clients/command_check.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <stdexcept>

#include "description/text.hpp"
#include "lcm_control/twist_t.hpp"
#include "tools/lib/clients/cm_client.hpp"

namespace lcm_control::tools {

std::string commanded_with(const controller_info_t& c) {
  const std::string& t = c.command_type;
  if (t == "joint_trajectory_t") return fmt::format("send-trajectory {} ...", c.name);
  if (t == "gripper_command_t") return fmt::format("gripper {} --position P", c.name);
  if (t == "twist_t") return fmt::format("drive {} LINEAR ANGULAR", c.name);
  if (t == "float64_t") return fmt::format("turret-cmd {} VALUE", c.name);
  if (t == "float64_array_t") {
    if (c.command_width <= 0) return fmt::format("turret-cmd {} VALUE... --array", c.name);
    std::vector<std::string> values;
    for (int k = 1; k <= c.command_width; ++k) values.push_back(fmt::format("V{}", k));
    return fmt::format("turret-cmd {} {}{}", c.name, fmt::join(values, " "), c.command_width == 1 ? " --array" : "");
  }
  if (t.empty()) return "";
  return fmt::format("bus pub {}/{} {} FIELD=VALUE...", c.name, c.command_channel.empty() ? "command" : c.command_channel,
                     t);
}

std::string type_mismatch(const controller_info_t& c, const Sent& sent, const std::string& channel,
                          const std::string& prefix) {
  const std::string use = commanded_with(c);
  if (c.command_type.empty())
    return fmt::format("{} ({}) takes no commands (it only reads the joints{}); {} was given on {}{}/{}: command a "
                       "controller that drives the joints instead (cmctl list)",
                       c.name, c.type,
                       c.publishes.empty() ? "" : fmt::format(" and publishes {}", fmt::join(c.publishes, ", ")),
                       sent.type, prefix, c.name, channel);
  const std::string own = c.command_channel.empty() ? "command" : c.command_channel;
  const std::string where = prefix + c.name + "/" + own;
  if (c.command_type != sent.type || channel != own)
    return fmt::format("{} takes {} on {}; {} was given{}: use {}", c.name, c.command_type, where, sent.type,
                       channel == own ? "" : " on " + prefix + c.name + "/" + channel, use);
  if (sent.width > 0 && c.command_width > 0 && sent.width != c.command_width)
    return fmt::format("{} takes {} of {} number{} on {} (one {} per joint: {}); {} were given: use {}", c.name,
                       c.command_type, c.command_width, c.command_width == 1 ? "" : "s", where,
                       c.command_quantity.empty() ? "value" : c.command_quantity, fmt::join(c.joints, ", "),
                       sent.width, use);
  return "";
}

const controller_info_t& commandable(const std::vector<controller_info_t>& listed, const std::string& name,
                                     const Sent& sent, const std::string& load_hint, const std::string& prefix) {
  std::vector<std::string> names;
  for (const auto& c : listed) {
    if (c.name != name) {
      names.push_back(c.name);
      continue;
    }
    if (const std::string bad = type_mismatch(c, sent, c.command_channel.empty() ? "command" : c.command_channel, prefix);
        !bad.empty())
      throw std::runtime_error(bad);
    if (c.state != "running")
      throw std::runtime_error(fmt::format("'{}' is loaded but {}, not running: start it with `cmctl start {}`", name,
                                           c.state, name));
    return c;
  }
  const std::string close = closest_name(name, names, 3);
  throw std::runtime_error(fmt::format(
      "no controller '{}' in the controller manager ({}): load and start it with `spawner {}`{}{}", name,
      names.empty() ? "none loaded" : fmt::format("loaded: {}", fmt::join(names, ", ")), name,
      load_hint.empty() ? "" : " " + load_hint, close.empty() ? "" : "; did you mean '" + close + "'?"));
}

const controller_info_t* controller_on(const std::vector<controller_info_t>& listed, const std::string& channel,
                                       std::string* relative) {
  for (const auto& c : listed) {
    const std::string head = c.name + "/";
    if (channel.size() <= head.size() || channel.compare(0, head.size(), head) != 0) continue;
    const std::string rest = channel.substr(head.size());
    if (rest != c.command_channel && rest != "command" && rest != "cmd_vel") continue;
    if (relative) *relative = rest;
    return &c;
  }
  return nullptr;
}

std::optional<cm_response_t> try_list(Bus& bus, const char* client, double timeout_s) {
  try {
    return CmClient(bus, client).list(timeout_s);
  } catch (const CmTimeout&) {
    return std::nullopt;
  }
}

namespace {
bool asked_about(const std::string& channel) {
  const auto slash = channel.rfind('/');
  if (slash == std::string::npos || channel == "hardware/command") return false;
  const std::string last = channel.substr(slash + 1);
  return last == "command" || last == "cmd_vel" || last == "reference" || last == "commands";
}
}  // namespace

void check_command_channel(Bus& bus, const std::string& channel, const Sent& sent, double timeout_s) {
  if (!asked_about(channel)) return;
  const std::optional<cm_response_t> r = try_list(bus, "bus", timeout_s);
  check_command_channel(bus, channel, sent, r ? &*r : nullptr);
}

void check_command_channel(Bus& bus, const std::string& channel, const Sent& sent, const cm_response_t* listed) {
  if (!listed || !asked_about(channel)) return;
  const cm_response_t& r = *listed;
  std::string relative;
  if (const controller_info_t* c = controller_on(r.controllers, channel, &relative)) {
    if (const std::string bad = type_mismatch(*c, sent, relative, bus.channel("")); !bad.empty())
      throw std::runtime_error(bad);
    return;
  }
  std::vector<std::string> channels;
  for (const controller_info_t& c : r.controllers)
    if (!c.command_channel.empty()) channels.push_back(bus.channel(c.name + "/" + c.command_channel));
  fmt::print(stderr, "bus: warning: no loaded controller takes commands on '{}': nothing listens there ({})\n",
             bus.channel(channel),
             channels.empty() ? std::string("no controller loaded takes commands")
                              : fmt::format("the controllers' command channels: {}", fmt::join(channels, ", ")));
}

std::string channel_from_ros(const std::string& name, const std::vector<controller_info_t>* listed, std::string* note) {
  if (note) note->clear();
  if (name.rfind("~/", 0) == 0 || name == "~")
    throw std::runtime_error(fmt::format("'{}' is a ROS private name (a node's own topic); write the controller's "
                                         "name instead: CONTROLLER/command (cmctl list shows them)",
                                         name));
  std::string out = name;
  while (!out.empty() && out.front() == '/') out.erase(0, 1);
  const auto slash = out.rfind('/');
  const std::string head = slash == std::string::npos ? "" : out.substr(0, slash);
  const std::string last = slash == std::string::npos ? out : out.substr(slash + 1);
  if (!head.empty() && (last == "follow_joint_trajectory" || last == "gripper_cmd"))
    throw std::runtime_error(fmt::format(
        "'{}' is a ROS action; send its goals with {} (it waits for the result as the action client does)", name,
        last == "gripper_cmd" ? fmt::format("gripper {} --position POSITION", head)
                              : fmt::format("send-trajectory {} --point TIME:POSITIONS", head)));
  if (!head.empty() && (last == "commands" || last == "joint_trajectory")) {
    const controller_info_t* c = nullptr;
    if (listed)
      for (const controller_info_t& x : *listed)
        if (x.name == head) c = &x;
    if (!c || c->command_channel.empty())
      out = head + "/command";
    else if (c->command_channel != last)
      out = head + "/" + c->command_channel;
  }
  if (note && out != name)
    *note = fmt::format("'{}' is ROS 2's name; here the channel is '{}'{}", name, out,
                        name.front() == '/' ? " (relative to --namespace)" : "");
  return out;
}

std::string twist_channel(Bus& bus, const std::string& controller, double timeout_s) {
  cm_response_t r;
  try {
    r = CmClient(bus, "drive").list(timeout_s);
  } catch (const CmTimeout&) {
    return "cmd_vel";
  }
  for (const controller_info_t& c : r.controllers)
    if (c.name == controller && c.command_type == twist_t::getTypeName() && !c.command_channel.empty())
      return c.command_channel;
  return "cmd_vel";
}

std::optional<std::string> hardware_cause(const cm_response_t& list) {
  // The words are controller_manager/hardware_status.cpp's (HardwareStatus::describe).
  const std::string& h = list.hardware;
  if (h.find("e-stop engaged") != std::string::npos)
    return std::string("the e-stop is engaged: the hardware holds still (release it: bus pub e_stop e_stop_t "
                       "engaged=false, or the dashboard's e-stop button)");
  if (h.find("the hardware is paused") != std::string::npos)
    return std::string("the simulator is paused: its time does not advance (cmctl resume)");
  if (h.find("SILENT") != std::string::npos)
    return std::string("the hardware is silent: the controller manager receives no hardware state (is sim_server "
                       "running?)");
  return std::nullopt;
}

std::string goal_failure(CmClient& cm, const std::string& controller, const std::string& status,
                         const std::string& message) {
  std::optional<std::string> cause;
  try {
    cause = hardware_cause(cm.list(1.0));
  } catch (const CmTimeout&) {
  }
  if (!cause) return fmt::format("{}: {}: {}", controller, status, message);
  return fmt::format("{}: {} because {}; the controller says: {}", controller, status, *cause, message);
}

}  // namespace lcm_control::tools
