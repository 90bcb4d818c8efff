#include "description/ros2_control.hpp"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "description/robot_model.hpp"
#include "description/text.hpp"

namespace lcm_control {

namespace {

std::string text_of(const tinyxml2::XMLElement* e) { return e && e->GetText() ? trim(e->GetText()) : ""; }
std::string attr(const tinyxml2::XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? trim(v) : "";
}

Ros2Params read_params(const tinyxml2::XMLElement* parent) {
  Ros2Params out;
  for (auto* p = parent->FirstChildElement("param"); p; p = p->NextSiblingElement("param"))
    out.emplace_back(attr(p, "name"), text_of(p));
  return out;
}

const std::string* find_param(const Ros2Params& params, const std::string& name) {
  for (const auto& [k, v] : params)
    if (k == name) return &v;
  return nullptr;
}

std::string moving_joints(const RobotModel& model) {
  std::vector<std::string> n;
  for (const auto& j : model.joints)
    if (j.type != JointType::Fixed) n.push_back(j.name);
  return n.empty() ? "none" : join(n);
}

std::string interface_names(const std::vector<Ros2Interface>& v) {
  std::vector<std::string> n;
  for (const auto& i : v) n.push_back(i.name);
  return join(n);
}

// Reads <command_interface>/<state_interface> children; `where` names the component for messages.
std::vector<Ros2Interface> read_interfaces(const tinyxml2::XMLElement* parent, const char* tag, const std::string& where,
                                           std::vector<std::string>& problems, std::vector<std::string>& warnings) {
  std::vector<Ros2Interface> out;
  for (auto* e = parent->FirstChildElement(tag); e; e = e->NextSiblingElement(tag)) {
    Ros2Interface i;
    i.name = attr(e, "name");
    i.data_type = attr(e, "data_type");
    i.params = read_params(e);
    if (i.name.empty()) {
      problems.push_back(fmt::format("{}: a <{}> has no name attribute; add name=\"position\" (or velocity, effort)",
                                     where, tag));
      continue;
    }
    const std::string what = fmt::format("{}: {} '{}'", where, tag, i.name);
    auto number = [&](const char* key, std::optional<double>& into, bool required) {
      const std::string* v = find_param(i.params, key);
      if (!v) return;
      double x = 0;
      if (parse_double(*v, x)) {
        into = x;
      } else if (required) {
        problems.push_back(fmt::format("{}: <param name=\"{}\"> '{}' is not a number", what, key, *v));
      } else {
        warnings.push_back(fmt::format("{}: <param name=\"{}\"> '{}' is not a number; ignored (as ros2_control does)",
                                       what, key, *v));
      }
    };
    number("min", i.min, false);
    number("max", i.max, false);
    // A bool/integer gpio or sensor value may have a non-numeric initial value ("false"); joints need numbers.
    const bool numeric = i.data_type.empty() || i.data_type == "double" || i.data_type == "float32" ||
                         i.data_type == "float64";
    number("initial_value", i.initial_value, numeric);
    if (i.min && i.max && *i.min > *i.max)
      problems.push_back(fmt::format("{}: min {:g} is above max {:g}; swap them", what, *i.min, *i.max));
    out.push_back(std::move(i));
  }
  return out;
}

Ros2Component read_component(const tinyxml2::XMLElement* e, const std::string& file, const std::string& block,
                             const char* kind, std::vector<std::string>& problems, std::vector<std::string>& warnings) {
  Ros2Component c;
  c.name = attr(e, "name");
  c.line = e->GetLineNum();
  const std::string where = fmt::format("{}:{}: ros2_control '{}': {} '{}'", file, c.line, block, kind, c.name);
  if (c.name.empty())
    problems.push_back(fmt::format("{}:{}: ros2_control '{}': a <{}> has no name attribute; add name=\"...\"", file,
                                   c.line, block, kind));
  c.command_interfaces = read_interfaces(e, "command_interface", where, problems, warnings);
  c.state_interfaces = read_interfaces(e, "state_interface", where, problems, warnings);
  c.params = read_params(e);
  return c;
}

// Narrows the joint's URDF limits by a command interface's min/max (ros2_control's update_interface_limits: the
// stricter wins); says what changed in `notes`.
void merge_limits(Joint& j, const Ros2Interface& i, const std::string& where, std::vector<std::string>& notes) {
  if ((!i.min && !i.max) || (i.min && i.max && *i.min > *i.max)) return;  // none, or refused already
  if (i.name == "position") {
    if (j.type == JointType::Continuous) {
      notes.push_back(fmt::format("{}: position command limits [{:g}, {:g}] recorded for the commands (ros2_control "
                                  "clamps commands to them); the continuous joint itself turns without limit",
                                  where, i.min.value_or(-INFINITY), i.max.value_or(INFINITY)));
      return;
    }
    if (!j.has_position_limits) return;
    const double lo = std::max(j.lower, i.min.value_or(-INFINITY)), hi = std::min(j.upper, i.max.value_or(INFINITY));
    if (lo != j.lower || hi != j.upper) {
      notes.push_back(fmt::format("{}: position min/max [{:g}, {:g}] is stricter than the URDF <limit> [{:g}, {:g}]; "
                                  "using [{:g}, {:g}]",
                                  where, i.min.value_or(-INFINITY), i.max.value_or(INFINITY), j.lower, j.upper, lo, hi));
      j.lower = lo;
      j.upper = hi;
    }
    return;
  }
  double* limit = i.name == "velocity" ? &j.velocity_limit : i.name == "effort" ? &j.effort_limit : nullptr;
  if (!limit) return;  // acceleration and others: kept on the interface
  double bound = INFINITY;
  if (i.max) bound = std::min(bound, std::abs(*i.max));
  if (i.min) bound = std::min(bound, std::abs(*i.min));
  if (bound < *limit) {
    notes.push_back(fmt::format("{}: {} min/max [{:g}, {:g}] is stricter than {}; using {:g}", where, i.name,
                                i.min.value_or(-INFINITY), i.max.value_or(INFINITY),
                                std::isinf(*limit) ? fmt::format("the URDF (no {} limit)", i.name)
                                                   : fmt::format("the URDF <limit {}=\"{:g}\">", i.name, *limit),
                                bound));
    *limit = bound;
  }
}

void read_block_transmission(HardwareBlock& block, const tinyxml2::XMLElement* t, const std::string& file,
                             std::vector<std::string>& problems, std::vector<std::string>& warnings) {
  Ros2Transmission tr;
  tr.name = attr(t, "name");
  tr.plugin = text_of(t->FirstChildElement("plugin"));
  const std::string where = fmt::format("{}:{}: ros2_control '{}': transmission '{}'", file, t->GetLineNum(),
                                        block.name, tr.name);
  std::vector<const tinyxml2::XMLElement*> joints, actuators;
  for (auto* j = t->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) joints.push_back(j);
  for (auto* a = t->FirstChildElement("actuator"); a; a = a->NextSiblingElement("actuator")) actuators.push_back(a);
  if (tr.plugin != "transmission_interface/SimpleTransmission") {
    warnings.push_back(fmt::format("{}: skipped: plugin '{}' is not supported (only "
                                   "transmission_interface/SimpleTransmission is)",
                                   where, tr.plugin));
    return;
  }
  if (joints.size() != 1 || actuators.size() != 1) {
    warnings.push_back(fmt::format("{}: skipped: a SimpleTransmission needs exactly one <joint> and one <actuator> "
                                   "(found {} and {})",
                                   where, joints.size(), actuators.size()));
    return;
  }
  tr.joint = attr(joints[0], "name");
  tr.actuator = attr(actuators[0], "name");
  auto number = [&](const char* tag, double& into) {
    std::string v = text_of(joints[0]->FirstChildElement(tag));
    if (v.empty()) v = text_of(actuators[0]->FirstChildElement(tag));
    if (v.empty()) return;
    if (!parse_double(v, into))
      problems.push_back(fmt::format("{}: <{}> '{}' is not a number", where, tag, v));
  };
  number("mechanical_reduction", tr.reduction);
  number("offset", tr.offset);
  if (tr.reduction == 0)
    problems.push_back(fmt::format("{}: <mechanical_reduction> is 0; a reduction ratio cannot be zero (use 1 for a "
                                   "direct drive, a negative value to flip the direction)",
                                   where));
  if (!block.joint(tr.joint)) {
    warnings.push_back(fmt::format("{}: joint '{}' is not a <joint> of this block; the transmission is ignored", where,
                                   tr.joint));
    return;
  }
  block.transmissions.push_back(std::move(tr));
}

}  // namespace

const char* to_string(HardwareKind k) { return k == HardwareKind::Mock ? "mock" : "simulator"; }

const Ros2Interface* Ros2Component::command_interface(const std::string& n) const {
  for (const auto& i : command_interfaces)
    if (i.name == n) return &i;
  return nullptr;
}
const Ros2Interface* Ros2Component::state_interface(const std::string& n) const {
  for (const auto& i : state_interfaces)
    if (i.name == n) return &i;
  return nullptr;
}
const Ros2Component* HardwareBlock::joint(const std::string& n) const {
  for (const auto& j : joints)
    if (j.name == n) return &j;
  return nullptr;
}

bool demo_hardware(const std::string& plugin) { return plugin.rfind("ros2_control_demo_", 0) == 0; }

std::optional<HardwareKind> hardware_kind(const std::string& plugin, std::string* rule) {
  const size_t slash = plugin.rfind("::") != std::string::npos ? plugin.rfind("::") + 1 : plugin.rfind('/');
  const std::string cls = slash == std::string::npos ? plugin : plugin.substr(slash + 1);
  const std::string pkg = slash == std::string::npos ? "" : plugin.substr(0, plugin.find_first_of("/:"));
  auto said = [&](HardwareKind k, std::string why) {
    if (rule) *rule = std::move(why);
    return std::optional<HardwareKind>(k);
  };
  for (const char* sim : {"GazeboSimSystem", "IgnitionSystem", "GazeboSystem"})
    if (cls == sim)
      return said(HardwareKind::Simulator, fmt::format("a Gazebo/gz simulator system (class {})", cls));
  if (cls.find("GzSystem") != std::string::npos || cls.find("GzSim") != std::string::npos)
    return said(HardwareKind::Simulator, fmt::format("a gz simulator system (class {})", cls));
  if (cls == "GenericSystem") return said(HardwareKind::Mock, "mock hardware (class GenericSystem)");
  // ros2_control_demos' example hardware (ros2_control_demo_example_N/RRBotSystem...): stand-ins whose state follows
  // the command, played as mock hardware.
  if (demo_hardware(plugin))
    return said(HardwareKind::Mock, fmt::format("ros2_control_demos' example hardware ({}), mock-like", pkg));
  return std::nullopt;
}

GpioInterfaces gpio_interfaces(const std::vector<HardwareBlock>& blocks) {
  GpioInterfaces out;
  for (const HardwareBlock& b : blocks)
    for (const Ros2Component& g : b.gpios) {
      for (const Ros2Interface& s : g.state_interfaces) {
        out.states.push_back(g.name + "/" + s.name);
        double v = s.initial_value.value_or(0.0);
        for (const auto& [k, text] : s.params)
          if (k == "initial_value" && (text == "true" || text == "True")) v = 1.0;
        out.initial.push_back(v);
      }
      for (const Ros2Interface& c : g.command_interfaces) out.commands.push_back(g.name + "/" + c.name);
    }
  return out;
}

bool has_ros2_control(const tinyxml2::XMLElement* robot) {
  return robot && robot->FirstChildElement("ros2_control") != nullptr;
}

void read_ros2_control(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                       std::vector<std::string>& problems) {
  int n_transmission_tags = 0;
  for (auto* t = robot->FirstChildElement("transmission"); t; t = t->NextSiblingElement("transmission"))
    ++n_transmission_tags;
  if (n_transmission_tags > 0)
    model.notes.push_back(fmt::format("{}: has both <transmission> tags ({}) and <ros2_control> blocks; the "
                                      "<ros2_control> blocks are used, as ROS 2 does, and the <transmission> tags are "
                                      "ignored",
                                      file, n_transmission_tags));
  std::map<std::string, std::pair<std::string, int>> listed;  // joint -> block, line (a joint is in one block)
  for (auto* b = robot->FirstChildElement("ros2_control"); b; b = b->NextSiblingElement("ros2_control")) {
    HardwareBlock block;
    block.name = attr(b, "name");
    block.type = attr(b, "type");
    block.line = b->GetLineNum();
    const std::string where = fmt::format("{}:{}: ros2_control '{}'", file, block.line, block.name);
    if (block.name.empty())
      problems.push_back(fmt::format("{}:{}: <ros2_control> has no name attribute; add name=\"...\"", file, block.line));
    const tinyxml2::XMLElement* hw = b->FirstChildElement("hardware");
    if (hw) {
      block.plugin = text_of(hw->FirstChildElement("plugin"));
      block.params = read_params(hw);
    }
    if (block.plugin.empty()) {
      problems.push_back(fmt::format("{}: no <hardware><plugin>; name simulated or mock hardware, e.g. "
                                     "<plugin>gz_ros2_control/GazeboSimSystem</plugin> or "
                                     "<plugin>mock_components/GenericSystem</plugin>",
                                     where));
    } else if (std::find(model.options.simulate_hardware.begin(), model.options.simulate_hardware.end(),
                         block.name) != model.options.simulate_hardware.end()) {
      block.kind = HardwareKind::Simulator;
      model.notes.push_back(fmt::format("{}: hardware plugin '{}' simulated in Bullet, as --simulate-hardware {} asks",
                                        where, block.plugin, block.name));
    } else if (std::string rule; const auto kind = hardware_kind(block.plugin, &rule)) {
      block.kind = *kind;
      static const std::set<std::string> standard = {"gz_ros2_control/GazeboSimSystem", "ign_ros2_control/IgnitionSystem",
                                                     "gazebo_ros2_control/GazeboSystem",
                                                     "mock_components/GenericSystem"};
      if (!standard.count(block.plugin))
        model.notes.push_back(fmt::format("{}: hardware plugin '{}' is {}: played as {} here", where, block.plugin,
                                          rule, *kind == HardwareKind::Mock ? "mock hardware" : "a simulator"));
    } else {
      problems.push_back(fmt::format(
          "{}: hardware plugin '{}' is neither a simulator nor mock hardware (a robot's driver or a package's own "
          "hardware) and cannot be simulated; expand the xacro with the argument that selects simulated or mock "
          "hardware (usually use_fake_hardware:=true, sim_gazebo:=true, use_gazebo:=true or sim_ignition:=true) so "
          "that the block names gz_ros2_control/GazeboSimSystem or mock_components/GenericSystem, or simulate it as it is "
          "with --simulate-hardware {} (a launch file's simulate_hardware: [{}])",
          where, block.plugin, block.name, block.name));
    }

    for (auto* je = b->FirstChildElement("joint"); je; je = je->NextSiblingElement("joint")) {
      Ros2Component c = read_component(je, file, block.name, "joint", problems, model.warnings);
      const std::string jwhere = fmt::format("{}:{}: ros2_control '{}': joint '{}'", file, c.line, block.name, c.name);
      if (c.name.empty()) continue;
      if (const auto it = listed.find(c.name); it != listed.end()) {
        problems.push_back(fmt::format("{}: is already in ros2_control '{}' (line {}); list each joint in one block",
                                       jwhere, it->second.first, it->second.second));
        continue;
      }
      listed[c.name] = {block.name, c.line};
      const Joint* j = model.joint(c.name);
      if (!j) {
        problems.push_back(fmt::format("{}: not in the URDF (moving joints: {})", jwhere, moving_joints(model)));
        continue;
      }
      if (j->type == JointType::Fixed) {
        problems.push_back(fmt::format("{}: the joint is fixed; fixed joints cannot be in ros2_control (remove it "
                                       "from the block or make it move)",
                                       jwhere));
        continue;
      }
      const std::string mimic_attr = attr(je, "mimic");
      if (mimic_attr == "true" && !j->mimic)
        problems.push_back(fmt::format("{}: mimic=\"true\" but the URDF joint has no <mimic>; add <mimic joint=...> "
                                       "to the URDF joint or remove the attribute",
                                       jwhere));
      c.mimic = j->mimic && mimic_attr != "false";
      if (find_param(c.params, "mimic") || find_param(c.params, "multiplier"))
        model.warnings.push_back(fmt::format("{}: <param name=\"mimic\"> / <param name=\"multiplier\"> is the old "
                                             "form, ignored (as ros2_control does since it was removed); the URDF "
                                             "<mimic> tag makes a mimic joint",
                                             jwhere));
      block.joints.push_back(std::move(c));
    }
    for (auto* se = b->FirstChildElement("sensor"); se; se = se->NextSiblingElement("sensor"))
      block.sensors.push_back(read_component(se, file, block.name, "sensor", problems, model.warnings));
    for (auto* ge = b->FirstChildElement("gpio"); ge; ge = ge->NextSiblingElement("gpio"))
      block.gpios.push_back(read_component(ge, file, block.name, "gpio", problems, model.warnings));
    for (auto* te = b->FirstChildElement("transmission"); te; te = te->NextSiblingElement("transmission"))
      read_block_transmission(block, te, file, problems, model.warnings);

    // Mimic rules, the start pose, limits and the actuators.
    for (const Ros2Component& c : block.joints) {
      Joint& j = *std::find_if(model.joints.begin(), model.joints.end(), [&](const Joint& x) { return x.name == c.name; });
      const std::string jwhere = fmt::format("{}:{}: ros2_control '{}': joint '{}'", file, c.line, block.name, c.name);
      if (c.mimic) {
        if (!c.command_interfaces.empty())
          problems.push_back(fmt::format("{}: mimics '{}' (URDF <mimic>) and has command interface {}; a mimic joint "
                                         "takes no commands: remove its <command_interface>s, or add mimic=\"false\" "
                                         "to drive it on its own",
                                         jwhere, j.mimic->joint, interface_names(c.command_interfaces)));
        if (!block.joint(j.mimic->joint))
          problems.push_back(fmt::format("{}: mimics '{}', which is not in this <ros2_control> block; list '{}' in "
                                         "it (ros2_control requires the mimicked joint in the same block)",
                                         jwhere, j.mimic->joint, j.mimic->joint));
        continue;
      }
      if (j.mimic) {  // mimic="false": driven on its own
        model.notes.push_back(fmt::format("{}: mimic=\"false\": driven on its own; the URDF <mimic joint=\"{}\"> is "
                                          "not simulated",
                                          jwhere, j.mimic->joint));
        j.mimic.reset();
      }
      for (const char* name : {"position", "velocity"}) {
        const Ros2Interface* s = c.state_interface(name);
        const Ros2Interface* cmd = c.command_interface(name);
        std::optional<double> v = s && s->initial_value ? s->initial_value : std::nullopt;
        if (!v && cmd && cmd->initial_value) v = cmd->initial_value;
        if (!v) continue;
        if (std::string(name) == "position")
          model.initial_positions[c.name] = *v;
        else
          model.initial_velocities[c.name] = *v;
        if (s && s->initial_value && cmd && cmd->initial_value && *cmd->initial_value != *s->initial_value)
          model.warnings.push_back(fmt::format("{}: {} initial_value {:g} on the state interface and {:g} on the "
                                               "command interface; the joint starts at the state's, {:g}",
                                               jwhere, name, *s->initial_value, *cmd->initial_value, *s->initial_value));
      }
      for (const Ros2Interface& i : c.command_interfaces) merge_limits(j, i, jwhere, model.notes);

      TransmissionSpec t;
      t.name = block.name + "/" + c.name;
      t.type = "transmission_interface/SimpleTransmission";
      t.joint = c.name;
      t.actuator = c.name + "_actuator";
      t.any_interface = true;
      std::vector<std::string> unsimulated;
      for (const Ros2Interface& i : c.command_interfaces) {
        if (const auto std_i = interface_of_quantity(i.name)) {
          if (std::find(t.interfaces.begin(), t.interfaces.end(), *std_i) == t.interfaces.end())
            t.interfaces.push_back(*std_i);
        } else {
          unsimulated.push_back(i.name);
        }
      }
      if (!unsimulated.empty())
        model.warnings.push_back(fmt::format("{}: command interface {} is read but not simulated (position, velocity "
                                             "and effort are){}",
                                             jwhere, join(unsimulated),
                                             t.interfaces.empty() ? "; the joint is not actuated" : ""));
      if (t.interfaces.empty()) {
        if (c.command_interfaces.empty())
          model.notes.push_back(fmt::format("{}: {}: it is not actuated (its state is reported)", jwhere,
                                            c.state_interfaces.empty() ? "no interfaces"
                                                                       : "state interfaces only"));
        continue;
      }
      t.hardware_block = block.name;
      for (const Ros2Transmission& tr : block.transmissions)
        if (tr.joint == c.name) {
          t.name = tr.name.empty() ? t.name : tr.name;
          if (!tr.actuator.empty()) t.actuator = tr.actuator;
          t.map.reduction = tr.reduction;
          t.map.offset = tr.offset;
        }
      model.transmissions.push_back(std::move(t));
    }
    for (const auto& g : block.gpios)
      model.notes.push_back(fmt::format("{}:{}: ros2_control '{}': gpio '{}' ({} command and {} state interfaces): a "
                                        "command interface echoes to the state interface of its name, as "
                                        "gz_ros2_control and mock hardware do",
                                        file, g.line, block.name, g.name, g.command_interfaces.size(),
                                        g.state_interfaces.size()));
    model.ros2_control.push_back(std::move(block));
  }
  for (const std::string& name : model.options.simulate_hardware) {
    std::vector<std::string> blocks;
    for (const HardwareBlock& b : model.ros2_control) blocks.push_back(b.name);
    if (std::find(blocks.begin(), blocks.end(), name) == blocks.end())
      problems.push_back(fmt::format("{}: --simulate-hardware {}: there is no <ros2_control name=\"{}\"> (the blocks: "
                                     "{}); name one of them",
                                     file, name, name, blocks.empty() ? "none" : join(blocks)));
  }
}

void read_ros2_control_plugin(RobotModel& model, const tinyxml2::XMLElement* robot, const std::string& file,
                              std::vector<std::string>& problems) {
  for (auto* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo"))
    for (auto* p = g->FirstChildElement("plugin"); p; p = p->NextSiblingElement("plugin")) {
      const std::string fn = attr(p, "filename");
      if (fn.find("ros2_control") == std::string::npos) continue;
      Ros2ControlPlugin& out = model.ros2_control_plugin;
      out.present = true;
      out.filename = fn;
      out.name = attr(p, "name");
      for (auto* f = p->FirstChildElement("parameters"); f; f = f->NextSiblingElement("parameters"))
        if (!text_of(f).empty()) out.parameters.push_back(text_of(f));
      if (auto* ros = p->FirstChildElement("ros")) out.ns = text_of(ros->FirstChildElement("namespace"));
      out.controller_manager_name = text_of(p->FirstChildElement("controller_manager_name"));
      if (const auto* h = p->FirstChildElement("hold_joints")) {
        const std::string v = text_of(h);
        if (v == "true" || v == "1")
          out.hold_joints = true;
        else if (v == "false" || v == "0")
          out.hold_joints = false;
        else
          problems.push_back(fmt::format("{}:{}: <plugin filename=\"{}\">: <hold_joints> '{}' is not a bool; write "
                                         "true (joints nobody commands are held still, the default) or false",
                                         file, h->GetLineNum(), fn, v));
      }
      if (const auto* k = p->FirstChildElement("position_proportional_gain")) {
        const std::string v = text_of(k);
        double gain = 0;
        if (!parse_double(v, gain)) {
          problems.push_back(fmt::format("{}:{}: <plugin filename=\"{}\">: <position_proportional_gain> '{}' is not "
                                         "a number; remove it (it is not used here) or give a number",
                                         file, k->GetLineNum(), fn, v));
        } else {
          out.position_proportional_gain = gain;
          model.notes.push_back(fmt::format("{}:{}: <position_proportional_gain> {:g} is ignored: a position command "
                                            "interface here is a servo on the position (direct, or a PID with "
                                            "pid_gains), not gz's proportional velocity loop",
                                            file, k->GetLineNum(), gain));
        }
      }
    }
}

}  // namespace lcm_control
