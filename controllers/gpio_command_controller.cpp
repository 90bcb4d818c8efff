// gpio_controllers/GpioCommandController (ros2_controllers): commands the <gpio> command interfaces its
// `command_interfaces` name per gpio of `gpios`, from an interface_group_values_t on `<name>/commands`
// (control_msgs/DynamicInterfaceGroupValues: groups are gpio names, each with interface names and values; a value
// stays until the next), and publishes the gpios' state interfaces (those `state_interfaces` names, else every state
// interface the URDF's <gpio> has) as an interface_group_values_t on `<name>/gpio_states` every update. Per gpio the
// interfaces are `{interfaces: [...]}`, or `[{interfaces: [...]}]` as ros2_control_demos write them.
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "controllers/factories.hpp"
#include "lcm_control/interface_group_values_t.hpp"

namespace lcm_control::cm {

namespace {

// `section`'s interfaces for `gpio` ({interfaces: [...]} or [{interfaces: [...]}]); empty when it names none.
std::vector<std::string> interfaces_of(const Params& p, const char* section, const std::string& gpio) {
  const YAML::Node all = p.node(section);
  if (!all) return {};
  const std::string where = fmt::format("{}/{}/{}", p.where(), section, gpio);
  if (!all.IsMap()) throw ControllerError(fmt::format("{}/{}: expected a map of gpio names", p.where(), section));
  YAML::Node n = all[gpio];
  if (!n) return {};
  if (n.IsSequence() && n.size() == 1 && n[0].IsMap()) n.reset(n[0]);
  if (!n.IsMap() || !n["interfaces"])
    throw ControllerError(where + ": expected {interfaces: [names]} (or a list holding it)");
  const YAML::Node list = n["interfaces"];
  if (!list.IsSequence()) throw ControllerError(where + "/interfaces: expected a list of interface names");
  std::vector<std::string> out;
  for (const auto& e : list) {
    if (!e.IsScalar() || e.Scalar().empty()) throw ControllerError(where + "/interfaces: every entry must be a name");
    if (std::find(out.begin(), out.end(), e.Scalar()) != out.end())
      throw ControllerError(fmt::format("{}/interfaces: '{}' is listed twice", where, e.Scalar()));
    out.push_back(e.Scalar());
  }
  return out;
}

class GpioCommandController : public Controller {
 public:
  void init(ControllerContext& ctx) override {
    Params& p = ctx.params();
    gpios_ = p.strings("gpios");
    for (const std::string& gpio : gpios_) {
      Group g;
      g.name = gpio;
      for (const auto& i : interfaces_of(p, "command_interfaces", gpio))
        g.commands.push_back({i, ctx.claim_gpio(gpio + "/" + i, "command_interfaces")});
      std::vector<std::string> states = interfaces_of(p, "state_interfaces", gpio);
      if (states.empty())  // every state interface of the gpio, as the URDF has them
        for (const GpioData& d : ctx.hardware_gpios())
          if (d.has_state && d.name.rfind(gpio + "/", 0) == 0) states.push_back(d.name.substr(gpio.size() + 1));
      for (const auto& i : states) g.states.push_back(ctx.read_gpio(gpio + "/" + i, "state_interfaces"));
      if (g.commands.empty() && g.states.empty())
        throw p.error("gpios", fmt::format("'{}' has no command or state interface here ({} declares none under that "
                                           "<gpio>, and command_interfaces names none)",
                                           gpio, ctx.model().urdf_path));
      if (!g.states.empty()) {
        state_msg_.interface_groups.push_back(gpio);
        interface_values_t v{};
        for (size_t k = 0; k < states.size(); ++k) v.interface_names.push_back(states[k]);
        v.num_interfaces = int32_t(states.size());
        v.values.assign(states.size(), 0.0);
        state_msg_.interface_values.push_back(v);
      }
      groups_.push_back(std::move(g));
    }
    state_msg_.num_groups = int32_t(state_msg_.interface_groups.size());
    const std::string name = ctx.name();
    auto bad = [this, name](const std::string& why) {
      if (dropped_++ % 100 == 0) spdlog::warn("{}: dropped a command: {} ({} dropped so far)", name, why, dropped_);
    };
    ctx.endpoints().subscribe<interface_group_values_t>(
        ctx.channel("commands"), [this, bad](const interface_group_values_t& m) { take(m, bad); }, bad);
    state_pub_ = ctx.endpoints().publisher<interface_group_values_t>(ctx.channel("gpio_states"));
  }

  void starting(const Time&) override {}

  void update(const Time& now, double) override {
    size_t m = 0;
    for (const Group& g : groups_) {
      if (g.states.empty()) continue;
      for (size_t k = 0; k < g.states.size(); ++k) state_msg_.interface_values[m].values[k] = g.states[k]->state;
      ++m;
    }
    state_msg_.utime = now.utime;
    state_pub_.publish(state_msg_);
  }

 private:
  struct Command {
    std::string interface;
    GpioData* gpio;
  };
  struct Group {
    std::string name;
    std::vector<Command> commands;
    std::vector<const GpioData*> states;
  };

  template <class Bad>
  void take(const interface_group_values_t& m, const Bad& bad) {
    if (int(m.interface_groups.size()) != m.num_groups || int(m.interface_values.size()) != m.num_groups)
      return bad(fmt::format("num_groups {} does not match the arrays", m.num_groups));
    for (int k = 0; k < m.num_groups; ++k) {
      const interface_values_t& v = m.interface_values[size_t(k)];
      if (int(v.interface_names.size()) != v.num_interfaces || int(v.values.size()) != v.num_interfaces)
        return bad(fmt::format("group '{}': num_interfaces {} does not match the arrays", m.interface_groups[size_t(k)],
                               v.num_interfaces));
      for (double x : v.values)
        if (!std::isfinite(x)) return bad(fmt::format("group '{}': a value is NaN or Inf", m.interface_groups[size_t(k)]));
    }
    for (int k = 0; k < m.num_groups; ++k) {
      const std::string& group = m.interface_groups[size_t(k)];
      const auto g = std::find_if(groups_.begin(), groups_.end(), [&](const Group& x) { return x.name == group; });
      const interface_values_t& v = m.interface_values[size_t(k)];
      for (int i = 0; i < v.num_interfaces; ++i) {
        const std::string& iface = v.interface_names[size_t(i)];
        Command* c = nullptr;
        if (g != groups_.end())
          for (Command& x : g->commands)
            if (x.interface == iface) c = &x;
        if (!c) {
          bad(fmt::format("'{}/{}' is not one of its command interfaces ({})", group, iface, commandable()));
          continue;
        }
        if (running_) c->gpio->command = v.values[size_t(i)];
      }
    }
  }

  std::string commandable() const {
    std::vector<std::string> all;
    for (const Group& g : groups_)
      for (const Command& c : g.commands) all.push_back(g.name + "/" + c.interface);
    return all.empty() ? "none" : fmt::format("{}", fmt::join(all, ", "));
  }

  std::vector<std::string> gpios_;
  std::vector<Group> groups_;
  interface_group_values_t state_msg_{};
  Publisher<interface_group_values_t> state_pub_;
};

}  // namespace

ControllerType gpio_command_controller() {
  ControllerTypeInfo t;
  t.name = "gpio_controllers/GpioCommandController";
  t.ros = RosVersion::Ros2;
  t.doc = "an interface_group_values_t on <name>/commands to <gpio> command interfaces; their states on "
          "<name>/gpio_states";
  t.command = {"interface_group_values_t", "commands", 0, ""};
  t.publishes = {};
  t.parameters = {
      ros2_parameter("gpios", "strings", "", "the <gpio> names"),
      ros2_parameter("command_interfaces", "map", "", "<gpio>: {interfaces: [names]}: the command interfaces it takes"),
      ros2_parameter("state_interfaces", "map", "",
                     "<gpio>: {interfaces: [names]}: the state interfaces it publishes (default: all of the gpio's)"),
  };
  return {t, [](const std::string&) { return std::make_unique<GpioCommandController>(); }};
}

}  // namespace lcm_control::cm
