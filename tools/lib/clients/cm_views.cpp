#include "tools/lib/clients/cm_views.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "tools/lib/clients/cm_client.hpp"
#include "tools/lib/clients/wait.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

namespace {

std::string us(double v) { return v > 0 ? fmt::format("{:.1f}", v) : "-"; }

struct StatisticsWatch {
  loop_stats_t cm{}, sim{};
  bool have_cm = false, have_sim = false;
  void on_cm(const lcm::ReceiveBuffer*, const std::string&, const loop_stats_t* m) {
    cm = *m;
    have_cm = true;
  }
  void on_sim(const lcm::ReceiveBuffer*, const std::string&, const loop_stats_t* m) {
    sim = *m;
    have_sim = true;
  }
};

std::string value_text(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "-"; }

// "component" -> the joints and other interfaces it has, from the LIST answer.
const hardware_component_t* component_of_joint(const cm_response_t& list, const std::string& joint) {
  for (const auto& c : list.components)
    if (std::find(c.joints.begin(), c.joints.end(), joint) != c.joints.end()) return &c;
  return nullptr;
}

}  // namespace

std::string statistics_text(const loop_stats_t& m) {
  std::string out = fmt::format(
      "{}: {} cycles, period {} µs mean ({} min, {} max, jitter {}), work {} µs mean ({} max), overruns {}, missed {}, "
      "dropped {}{}\n",
      m.process, m.cycles, us(m.period_mean_us), us(m.period_min_us), us(m.period_max_us), us(m.period_jitter_us),
      us(m.exec_mean_us), us(m.exec_max_us), m.overruns, m.missed, m.dropped,
      m.real_time_factor > 0 ? fmt::format(", real-time factor {:.3f}", m.real_time_factor) : "");
  if (m.num_items == 0) return out;
  std::vector<std::vector<std::string>> rows = {{"  ITEM", "KIND", "UPDATES", "EXEC MEAN", "EXEC P99", "EXEC MAX",
                                                 "PERIOD MEAN", "PERIOD P99", "PERIOD MAX"}};
  for (int k = 0; k < m.num_items; ++k) {
    const size_t i = size_t(k);
    const auto at = [&](const std::vector<double>& v) { return i < v.size() ? us(v[i]) : "-"; };
    rows.push_back({"  " + m.item[i], i < m.item_kind.size() ? m.item_kind[i] : "-",
                    i < m.item_count.size() ? std::to_string(m.item_count[i]) : "-", at(m.item_exec_mean_us),
                    at(m.item_exec_p99_us), at(m.item_exec_max_us), at(m.item_period_mean_us),
                    at(m.item_period_p99_us), at(m.item_period_max_us)});
  }
  return out + table_text(rows, 1) + "  (µs; over the last window of about 1 s)\n";
}

std::string wait_statistics(Bus& bus, double timeout_s) {
  StatisticsWatch w;
  const int a = subscribe_guarded<&StatisticsWatch::on_cm>(bus, bus.channel(channels::kCmStatistics), &w);
  const int b = subscribe_guarded<&StatisticsWatch::on_sim>(bus, bus.channel(channels::kSimStatistics), &w);
  pump_until(bus, [&] { return w.have_cm && w.have_sim; }, timeout_s);
  if (!w.have_cm) pump_until(bus, [&] { return w.have_cm; }, 0.0);
  bus.unsubscribe(a);
  bus.unsubscribe(b);
  if (!w.have_cm)
    throw BusError(fmt::format("no statistics from the controller manager within {} on '{}' (it publishes them once a "
                               "second): is controller_manager running on {}? (same --lcm-url and --namespace)",
                               seconds_text(timeout_s), bus.channel(channels::kCmStatistics), bus.url()));
  return statistics_text(w.cm) + (w.have_sim ? statistics_text(w.sim) : "");
}

std::string hardware_status_text(const cm_response_t& list) {
  if (list.components.empty()) return "no hardware components (the robot has no transmissions and no <ros2_control>)\n";
  std::string out = list.hardware.empty() ? "" : "hardware: " + list.hardware + "\n";
  for (const auto& c : list.components) {
    out += fmt::format("{} ({}, {}): {}{}\n", c.name, c.type, c.plugin.empty() ? c.kind : c.plugin, c.state_label,
                       c.error.empty() ? "" : " after an error: " + c.error);
    std::vector<std::vector<std::string>> rows = {{"    INTERFACE", "KIND", "VALUE", "CLAIMED BY"}};
    for (const auto& j : list.joints) {
      if (std::find(c.joints.begin(), c.joints.end(), j.joint) == c.joints.end()) continue;
      for (const auto& k : j.command)
        rows.push_back({"    " + j.joint + "/" + k, "command", k == j.claimed ? value_text(j.command_value) : "-",
                        k == j.claimed ? j.claimed_by : "-"});
      for (size_t s = 0; s < j.state.size(); ++s)
        rows.push_back({"    " + j.joint + "/" + j.state[s], "state",
                        s < j.state_value.size() ? value_text(j.state_value[s]) : "-", ""});
    }
    for (size_t i = 0; i < c.interfaces.size(); ++i)
      rows.push_back({"    " + c.interfaces[i], "state",
                      i < c.interface_values.size() ? value_text(c.interface_values[i]) : "-", ""});
    if (rows.size() > 1) out += table_text(rows, 1);
  }
  return out;
}

namespace {
// The controller whose reference interface `joint` is ("<controller>/<dof>", ROS 2 chaining), or nullptr.
const controller_info_t* exporter_of(const std::vector<controller_info_t>& listed, const std::string& joint) {
  const size_t slash = joint.find('/');
  if (slash == std::string::npos) return nullptr;
  for (const auto& c : listed)
    if (c.name == joint.substr(0, slash)) return &c;
  return nullptr;
}
}  // namespace

std::string joint_behind(const std::vector<controller_info_t>& listed, const std::string& name) {
  std::string at = name;
  for (size_t hops = 0; hops <= listed.size(); ++hops) {
    const controller_info_t* exporter = exporter_of(listed, at);
    if (!exporter) return at;
    at = at.substr(exporter->name.size() + 1);
  }
  return at;
}

namespace {
// "velocity" of "VelocityJointInterface".
std::string quantity_in(const std::string& hardware_interface) {
  std::string q = hardware_interface.substr(0, hardware_interface.find("JointInterface"));
  for (char& c : q) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return q;
}
}  // namespace

std::string controller_chains_text(const cm_response_t& list) {
  std::string out;
  size_t chained = 0;
  for (const auto& ctl : list.controllers) {
    out += fmt::format("{} ({}, {})\n", ctl.name, ctl.type, list.ros2 ? ros2_state(ctl.state) : ctl.state);
    std::set<std::string> components;
    for (const auto& j : ctl.joints)
      if (const controller_info_t* to = exporter_of(list.controllers, j)) {
        out += fmt::format("  writes {}/{} -> {} (its reference interface)\n", j, quantity_in(ctl.hardware_interface),
                           to->name);
        ++chained;
      }
    for (const auto& j : list.joints)
      if (j.claimed_by == ctl.name) {
        const hardware_component_t* c = component_of_joint(list, j.joint);
        out += fmt::format("  commands {}/{} -> {}\n", j.joint, j.claimed, c ? c->name : "-");
      }
    for (const auto& c : list.components)
      if (std::find(c.controllers.begin(), c.controllers.end(), ctl.name) != c.controllers.end())
        components.insert(c.name);
    out += fmt::format("  uses hardware components: {}\n",
                       components.empty() ? "-" : fmt::format("{}", fmt::join(components, ", ")));
  }
  if (chained == 0) out += "no chained controllers: each claims hardware interfaces only\n";
  return out;
}

std::string controller_chains_dot(const cm_response_t& list) {
  std::string out = "digraph controller_chains {\n  rankdir=LR;\n  node [shape=box];\n";
  for (const auto& c : list.components)
    out += fmt::format("  \"hw:{}\" [label=\"{}\\n{}\", shape=box3d];\n", c.name, c.name, c.state_label);
  for (const auto& ctl : list.controllers) {
    out += fmt::format("  \"{}\" [label=\"{}\\n{}\"];\n", ctl.name, ctl.name,
                       list.ros2 ? ros2_state(ctl.state) : ctl.state);
    for (const auto& j : ctl.joints)
      if (const controller_info_t* to = exporter_of(list.controllers, j))
        out += fmt::format("  \"{}\" -> \"{}\" [label=\"{}/{}\"];\n", ctl.name, to->name, j,
                           quantity_in(ctl.hardware_interface));
    for (const auto& c : list.components) {
      if (std::find(c.controllers.begin(), c.controllers.end(), ctl.name) == c.controllers.end()) continue;
      std::vector<std::string> claimed;
      for (const auto& j : list.joints)
        if (j.claimed_by == ctl.name && std::find(c.joints.begin(), c.joints.end(), j.joint) != c.joints.end())
          claimed.push_back(j.joint + "/" + j.claimed);
      out += fmt::format("  \"{}\" -> \"hw:{}\" [label=\"{}\"{}];\n", ctl.name, c.name,
                         claimed.empty() ? "reads" : fmt::format("{}", fmt::join(claimed, "\\n")),
                         claimed.empty() ? ", style=dashed" : "");
    }
  }
  return out + "}\n";
}

}  // namespace lcm_control::tools
