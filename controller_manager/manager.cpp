#include "controller_manager/manager.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "bus/hardware_wire.hpp"
#include "bus/messages.hpp"
#include "bus/run_config.hpp"
#include "description/text.hpp"
#include "description/control_config.hpp"
#include "description/model_check.hpp"
#include "rt/scheduling.hpp"
#include "controller_interface/claims.hpp"
#include "controller_manager/context.hpp"
#include "controller_manager/gains.hpp"
#include "controller_manager/ros_catalog.hpp"
#include "controller_manager/switch_plan.hpp"
#include "lcm_control/cm_request_t.hpp"
#include "lcm_control/float64_array_t.hpp"
#include "lcm_control/float64_t.hpp"

namespace lcm_control::cm {

namespace {
const char* const kShuttingDown = "the controller manager is shutting down";

// On udpm:// the outbox sends on an lcm::LCM of its own: its own socket and lock, so that a send in progress never
// holds up the loop's hardware/command. Other providers (memq://) are in-process: only the bus's instance reaches it.
std::unique_ptr<lcm::LCM> outbox_lcm(const Bus& bus) {
  if (bus.url().rfind("udpm://", 0) != 0) return nullptr;
  auto lc = std::make_unique<lcm::LCM>(bus.url());
  if (!lc->good()) throw std::runtime_error("cannot open LCM at " + bus.url() + " to send the controllers' messages");
  return lc;
}
// What its type declares it takes and publishes; for a type that declares nothing, the numbers it takes
// (ControllerContext::take_commands).
void describe_command(const ControllerTypeInfo* info, const Controller& controller, controller_info_t& out) {
  out.command_width = 0;
  if (info && !info->command.type.empty()) {
    const CommandInfo& c = info->command;
    out.command_type = c.type;
    out.command_channel = c.channel;
    out.command_width = c.width == CommandInfo::kOnePerJoint ? out.num_joints : c.width;
    out.command_quantity = c.quantity;
    if (c.quantity.empty() && c.width != 0 && controller.claim().interface)
      out.command_quantity = quantity_of(*controller.claim().interface);
  } else if (const CommandInput* in = controller.command_input()) {
    out.command_type = in->array ? float64_array_t::getTypeName() : float64_t::getTypeName();
    out.command_channel = "command";
    out.command_width = static_cast<int32_t>(in->width);
  }
  if (info) out.publishes = info->publishes;
  out.num_publishes = static_cast<int32_t>(out.publishes.size());
  out.chainable = info && info->chainable;
  out.chained_mode = controller.chained_mode();
  for (const JointData* r : controller.exported())
    for (const Interface x : r->offered) out.references.push_back(r->name + "/" + quantity_of(x));
  out.num_references = static_cast<int32_t>(out.references.size());
}
}  // namespace

ControllerManager::ControllerManager(RobotModel model, Bus& bus, const Registry& registry, ManagerOptions options)
    : model_(std::move(model)),
      bus_(bus),
      registry_(registry),
      options_(options),
      outbox_lcm_(outbox_lcm(bus)),
      outbox_(outbox_lcm_ ? *outbox_lcm_ : bus.lcm()),
      intake_(options_.intake_thread ? std::make_unique<Intake>() : nullptr),
      hw_(model_),
      loop_(hw_),
      endpoints_(bus, Endpoints::On::Shared),
      hw_endpoints_(bus, Endpoints::On::Hardware),
      sources_(loop_, bus),
      command_pub_(hw_endpoints_.publisher<hardware_command_t>(bus.channel(channels::kHardwareCommand))),
      stats_pub_(endpoints_.publisher<loop_stats_t>(bus.channel(channels::kCmStatistics))),
      activity_pub_(endpoints_.publisher<activity_t>(bus.channel(channels::kCmActivity))),
      inputs_(bus, Publisher<cm_inputs_t>(&bus.lcm(), bus.channel(channels::kCmInputs), &outbox_)) {
  loop_.set_before_update(&sources_);
  if (intake_) intake_->set_hooks([this] { inputs_.submitted_off_loop(); }, [this] { inputs_.result_taken(); });
  configured_ = index_of(model_.controllers);
  hw_endpoints_.subscribe<hardware_state_t>(
      bus.channel(channels::kHardwareState),
      [this](const hardware_state_t& m) {
        const std::string why = check(m);
        if (!why.empty()) {
          if (bad_state_logged_++ % 1000 == 0)
            spdlog::warn("dropped a malformed hardware/state ({}); {} so far", why, bad_state_logged_);
          ++dropped_;
          return;
        }
        on_hardware_state(m);
      },
      [this](const std::string& why) {
        if (bad_state_logged_++ % 1000 == 0) spdlog::warn("dropped hardware/state: {}", why);
        ++dropped_;
      },
      [n = int(model_.transmissions.size()),
       m = std::max(sensor_value_count(model_.sensors) + int(gpio_interfaces(model_.ros2_control).states.size()),
                    int(hw_.components().size()))](const void* data, size_t size) {
        return check_hardware_state_bytes(data, size, n, m);
      });
}

ControllerManager::~ControllerManager() {
  shutdown();
  if (intake_) intake_->set_hooks({}, {});
}

std::unordered_map<std::string, size_t> ControllerManager::index_of(const std::vector<ControllerSpec>& controllers) {
  std::unordered_map<std::string, size_t> index;
  for (size_t k = 0; k < controllers.size(); ++k) index.emplace(controllers[k].name, k);
  return index;
}

ControllerSlot* ControllerManager::find(const std::string& name) const {
  for (const auto& s : loop_.slots())
    if (s->name == name) return s.get();
  return nullptr;
}

std::string ControllerManager::names_loaded() const {
  std::vector<std::string> v;
  for (const auto& s : loop_.slots()) v.push_back(s->name);
  return v.empty() ? "none" : join_some(v, 20);
}

namespace {
constexpr size_t kShownLines = 20;  // per-name lines in one batch reply; beyond them, counts

// The first 20 of `count` names, then "(and N more)", without copying the others.
std::string some_names(size_t count, const std::function<const std::string&(size_t)>& name) {
  if (count == 0) return "none";
  std::vector<std::string> first;
  for (size_t k = 0; k < std::min<size_t>(count, 20); ++k) first.push_back(name(k));
  return join(first) + (count > 20 ? fmt::format(" (and {} more)", count - 20) : "");
}
}  // namespace

std::string ControllerManager::names_configured() const {
  return some_names(model_.controllers.size(), [this](size_t k) -> const std::string& { return model_.controllers[k].name; });
}

Reply ControllerManager::each(const std::vector<std::string>& names, bool load) {
  Batch b;
  b.names = names;
  b.load = load;
  while (!step(b, std::numeric_limits<int64_t>::max())) {
  }
  return b.reply;
}

bool ControllerManager::step(Batch& b, int64_t deadline_us) {
  Reply& all = b.reply;
  while (b.next < b.names.size()) {
    const std::string& n = b.names[b.next++];
    if (!(find(n) || (b.load && configured_.count(n)))) {
      b.unknown.push_back(n);
      continue;
    }
    const Reply one = b.load ? load(n) : unload(n);
    all.ok = all.ok && one.ok;
    if (b.shown < kShownLines) {
      all.message += (all.message.empty() ? "" : "; ") + one.message;
      ++b.shown;
    } else {
      ++(one.ok ? b.done : b.refused);
    }
    if (monotonic_us() >= deadline_us) return false;
  }
  if (b.done + b.refused > 0)
    all.message += fmt::format("; and {} more: {} {}, {} refused", b.done + b.refused, b.done,
                               b.load ? "loaded" : "unloaded", b.refused);
  if (b.unknown.empty()) return true;
  if (b.unknown.size() == 1 && b.names.size() == 1) {
    all = b.load ? load(b.unknown[0]) : unload(b.unknown[0]);
    return true;
  }
  const std::string& first = b.unknown[0];
  const size_t candidates = b.load ? model_.controllers.size() : loop_.slots().size();
  auto candidate = [&](size_t k) -> const std::string& {
    return b.load ? model_.controllers[k].name : loop_.slots()[k]->name;
  };
  while (first.size() <= 256 && b.near_at < candidates) {
    const std::string& c = candidate(b.near_at++);
    const size_t apart = c.size() > first.size() ? c.size() - first.size() : first.size() - c.size();
    if (apart < b.near_distance) {
      const size_t d = edit_distance(first, c);
      if (d < b.near_distance) b.near_distance = d, b.near = c;
    }
    if (b.near_at % 64 == 0 && monotonic_us() >= deadline_us) return false;
  }
  std::vector<std::string> quoted;
  for (size_t k = 0; k < std::min<size_t>(b.unknown.size(), 5); ++k)
    quoted.push_back("'" + clip(b.unknown[k], 60) + "'");
  if (b.unknown.size() > 5) quoted.push_back(fmt::format("(and {} more)", b.unknown.size() - 5));
  const std::string listed = some_names(candidates, candidate);
  all.ok = false;
  all.message += (all.message.empty() ? "" : "; ") +
                 fmt::format("cannot {} {} controller(s) {}: {}{} ({} controllers: {})", b.load ? "load" : "unload",
                             b.unknown.size(),
                             b.load ? "with no entry in the config " + model_.config_path : "not loaded",
                             join(quoted), b.near.empty() ? "" : fmt::format(" (did you mean '{}'?)", b.near),
                             b.load ? "configured" : "loaded", listed);
  return true;
}

std::string ControllerManager::yaml_key(const std::string& controller) const {
  return model_.config_section.empty() ? controller : model_.config_section + "/" + controller;
}

double ControllerManager::own_update_rate(const Params& params) const {
  const double hz = params.number("update_rate");
  if (!(hz > 0) || !std::isfinite(hz))
    throw params.error("update_rate", fmt::format("{} Hz: must be > 0 (leave it out to update on every cycle of the "
                                                  "controller manager)",
                                                  hz));
  if (model_.update_rate_hz && hz > *model_.update_rate_hz + 1e-9)
    throw params.error("update_rate", fmt::format("{:g} Hz is above the controller manager's update_rate {:g} Hz ({}); "
                                                  "a controller updates at most once a cycle: give it {:g} or less",
                                                  hz, *model_.update_rate_hz, model_.config_path,
                                                  *model_.update_rate_hz));
  return hz;
}

std::vector<std::string> ControllerManager::fallback_controllers(const std::string& name, const Params& params) const {
  const YAML::Node n = params.node("fallback_controllers");
  if (n.IsSequence() && n.size() == 0) return {};
  const std::vector<std::string> names = params.strings("fallback_controllers");
  for (const std::string& f : names) {
    if (f == name)
      throw params.error("fallback_controllers", fmt::format("'{}' is the controller itself; name the controllers to "
                                                             "start when it fails",
                                                             f));
    if (!configured_.count(f))
      throw params.error("fallback_controllers",
                         fmt::format("'{}' is not a controller of {} (configured controllers: {})", clip(f),
                                     model_.config_path, names_configured()));
  }
  return names;
}

namespace {
// Whether a ROS 2 controller asks for its own thread (instantiate() reads and checks the parameter).
bool wants_async(const ControllerSpec& spec) {
  const YAML::Node& params = spec.params;
  try {
    return params.IsMap() && params["is_async"] && params["is_async"].as<bool>();
  } catch (const YAML::Exception&) {
    return false;
  }
}
}  // namespace

ControllerCheck ControllerManager::instantiate(const ControllerSpec& spec, Endpoints& endpoints,
                                               std::unique_ptr<Controller>* out, std::unique_ptr<Hardware>* shadow,
                                               bool checking) {
  ControllerCheck c{spec.name, spec.type, ControllerCheck::Loads, "", {}, 0, {}};
  auto controller = registry_.create(spec.type);
  if (!controller) {
    c.outcome = registry_.misspelling(spec.type) ? ControllerCheck::Refused : ControllerCheck::NotImplemented;
    c.message = fmt::format("{}: {}/type: {}", model_.config_file_of(yaml_key(spec.name) + "/type"), yaml_key(spec.name),
                            unknown_type_message(registry_, spec.type));
    return c;
  }
  Params params(spec.params, fmt::format("{}: {}", spec.file, yaml_key(spec.name)));
  std::unique_ptr<Hardware> own;
  if (model_.ros2_parameter_file && params.has("is_async")) {  // ROS 2: its updates run on a thread of its own
    try {
      c.is_async = params.boolean("is_async", false);
    } catch (const std::exception& e) {
      c.outcome = ControllerCheck::Refused;
      c.message = e.what();
      return c;
    }
    if (c.is_async) own = std::make_unique<Hardware>(model_);
  }
  const ControllerTypeInfo* info = registry_.info(spec.type);
  HardwareContext ctx(spec.name, spec.type, params, model_, own ? *own : hw_, bus_, endpoints, info);
  ctx.self() = controller.get();
  ctx.set_checking(checking);
  try {
    controller->init(ctx);
  } catch (const InterfaceError& e) {
    c.outcome = ControllerCheck::InterfaceMismatch;
    c.message = e.what();
    return c;
  } catch (const std::exception& e) {
    c.outcome = ControllerCheck::Refused;
    c.message = e.what();
    return c;
  }
  if (info) {
    if (const std::string why = undeclared_claim(*info, spec.params, controller->claim()); !why.empty()) {
      c.outcome = ControllerCheck::Refused;
      c.message = fmt::format("{}: type '{}' does not do what it declares: {} (its ControllerTypeInfo::claims is "
                              "to say it)",
                              params.where(), spec.type, why);
      return c;
    }
  }
  c.notes = std::move(ctx.notes);
  if (params.has("plugin")) params.node("plugin");  // the controller library, loaded before (plugins.hpp)
  // Every ROS 2 node has use_sim_time; here controllers always run on the simulator's clock.
  if (model_.ros2_parameter_file && params.has("use_sim_time")) params.node("use_sim_time");
  if (model_.ros2_parameter_file && params.has("update_rate")) {  // every ROS 2 controller's own rate
    try {
      c.update_rate_hz = own_update_rate(params);
    } catch (const std::exception& e) {
      c.outcome = ControllerCheck::Refused;
      c.message = e.what();
      return c;
    }
    if (model_.update_rate_hz && std::abs(std::remainder(*model_.update_rate_hz, c.update_rate_hz)) > 1e-9)
      c.notes.push_back(fmt::format("{}/update_rate: {:g} Hz does not divide the controller manager's {:g} Hz; it "
                                    "updates every {} cycles ({:g} Hz)",
                                    params.where(), c.update_rate_hz, *model_.update_rate_hz,
                                    std::lround(*model_.update_rate_hz / c.update_rate_hz),
                                    *model_.update_rate_hz / double(std::lround(*model_.update_rate_hz / c.update_rate_hz))));
  }
  if (model_.ros2_parameter_file && params.has("fallback_controllers")) {  // ROS 2: started when it fails
    try {
      c.fallbacks = fallback_controllers(spec.name, params);
    } catch (const std::exception& e) {
      c.outcome = ControllerCheck::Refused;
      c.message = e.what();
      return c;
    }
  }
  const std::vector<std::string> known = info ? parameter_names(*info) : std::vector<std::string>{};
  for (const auto& k : params.unused()) {
    const std::string where =
        fmt::format("{}: {}/{}", model_.config_file_of(yaml_key(spec.name) + "/" + k), yaml_key(spec.name), k);
    if (std::find(known.begin(), known.end(), k) != known.end()) {
      c.notes.push_back(fmt::format("{}: known ROS parameter of {}, not supported yet; ignored", where, spec.type));
      continue;
    }
    const std::string near = closest_name(k, known, 3);
    c.notes.push_back(fmt::format("{}: not a parameter of {}; ignored{}", where, spec.type,
                                  near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near)));
  }
  if (out) *out = std::move(controller);
  if (shadow) *shadow = std::move(own);
  return c;
}

Reply ControllerManager::load(const std::string& name) {
  if (shutting_down_) return {false, kShuttingDown};
  if (ControllerSlot* s = find(name))
    return {false, fmt::format("cannot load '{}': it is already loaded (state: {})", name, s->state())};
  const auto at = configured_.find(name);
  const ControllerSpec* spec = at == configured_.end() ? nullptr : &model_.controllers[at->second];
  if (!spec) {
    return {false, fmt::format("cannot load '{}': there is no '{}' entry with a type in the config {} (configured "
                               "controllers: {})",
                               clip(name), clip(yaml_key(name)), model_.config_path, names_configured())};
  }
  auto slot = std::make_unique<ControllerSlot>();
  slot->name = name;
  slot->type = spec->type;
  slot->endpoints = std::make_unique<Endpoints>(bus_, Endpoints::On::Shared);
  if (model_.ros2_parameter_file && wants_async(*spec)) slot->outbox = std::make_unique<Outbox>(outbox_lcm_ ? *outbox_lcm_ : bus_.lcm());
  slot->endpoints->set_outbox(slot->outbox ? slot->outbox.get() : &outbox_);
  slot->endpoints->set_intake(intake_.get());
  const ControllerCheck c = instantiate(*spec, *slot->endpoints, &slot->controller, &slot->shadow);
  if (c.outcome != ControllerCheck::Loads)
    return {false, c.outcome == ControllerCheck::NotImplemented || c.message.rfind(spec->file, 0) == 0
                       ? fmt::format("cannot load '{}': {}", name, c.message)
                       : fmt::format("cannot load '{}' ({}): {}", name, spec->type, c.message)};
  slot->update_rate_hz = c.update_rate_hz;
  slot->fallbacks = c.fallbacks;
  slot->fallback_started.assign(c.fallbacks.size(), 0);
  if (slot->controller->claim().interface)
    for (const auto& j : slot->controller->claim().joints) slot->claimed.push_back(hw_.find(j));
  for (const auto& g : slot->controller->claim().gpios) slot->claimed_gpios.push_back(hw_.gpio(g));
  if (!slot->controller->pid_joints().empty()) serve_gains(*slot, bus_);
  if (slot->shadow) {  // its handlers wait while its update runs; its thread publishes through an outbox of its own
    slot->async = std::make_unique<AsyncUpdate>(*slot->controller, *slot->shadow);
    slot->endpoints->hold_while([a = slot->async.get()] { return a->busy(); });
  }
  const std::string claims = describe(slot->controller->claim());
  if (!slot->controller->exported().empty() && slot->async)
    return {false, fmt::format("cannot load '{}': a chainable controller with is_async is not implemented; leave "
                               "is_async out",
                               name)};
  for (const JointData* j : slot->claimed)
    if (j && !j->exported_by.empty() && slot->async)
      return {false, fmt::format("cannot load '{}': writing reference interfaces with is_async is not implemented; "
                                 "leave is_async out",
                                 name)};
  hw_.set_references_live(name, true);
  loop_.slots().push_back(std::move(slot));
  loop_.reorder();
  for (const auto& n : c.notes) spdlog::warn("{}", n);
  changed();
  std::string msg = fmt::format("loaded '{}' ({}), claims {}; state initialized", name, spec->type, claims);
  if (!c.notes.empty()) msg += "; note: " + join(c.notes, "; ");
  return {true, msg};
}

std::vector<ControllerCheck> ControllerManager::check_configured() {
  // Chained controllers may come in any order: those that wrote another's reference interfaces before it was
  // checked (and so exported them) are checked again once every other one was.
  std::vector<ControllerCheck> out;
  std::vector<size_t> again;
  for (size_t k = 0; k < model_.controllers.size(); ++k) {
    Endpoints scratch(bus_, Endpoints::On::Shared);  // unsubscribes whatever init() subscribed
    out.push_back(instantiate(model_.controllers[k], scratch, nullptr, nullptr, true));
    if (out.back().outcome != ControllerCheck::Loads && out.back().message.find("has exported no reference interface") !=
                                                             std::string::npos)
      again.push_back(k);
  }
  for (size_t k : again) {
    Endpoints scratch(bus_, Endpoints::On::Shared);
    out[k] = instantiate(model_.controllers[k], scratch, nullptr, nullptr, true);
  }
  return out;
}

Reply ControllerManager::unload(const std::string& name) {
  ControllerSlot* s = find(name);
  if (!s) return {false, fmt::format("cannot unload '{}': it is not loaded (loaded: {})", clip(name), names_loaded())};
  if (s->running)
    return {false, fmt::format("cannot unload '{}': it is running; stop it first (switch with stop=[{}])", name, name)};
  if (busy()) return {false, fmt::format("cannot unload '{}' now: a switch is being applied; retry", name)};
  for (const auto& other : loop_.slots())
    for (const JointData* j : other->claimed)
      if (j && j->exported_by == name)
        return {false, fmt::format("cannot unload '{}': '{}' claims its reference interface '{}'; unload '{}' first",
                                   name, other->name, j->name, other->name)};
  sources_.end_for(name, "controller unloaded");
  hw_.set_references_live(name, false);
  auto& slots = loop_.slots();
  for (auto it = slots.begin(); it != slots.end(); ++it)
    if (it->get() == s) {
      std::unique_ptr<ControllerSlot> gone = std::move(*it);
      slots.erase(it);
      loop_.reorder();
      retire(std::move(gone));
      break;
    }
  changed();
  return {true, fmt::format("unloaded '{}'", name)};
}

void ControllerManager::retire(std::unique_ptr<ControllerSlot> slot) {
  if (options_.slice_us > 0) retired_.push_back(std::move(slot));
}

void ControllerManager::switch_controllers(const std::vector<std::string>& start, const std::vector<std::string>& stop,
                                           int strictness, Done done) {
  if (shutting_down_) return done({false, kShuttingDown});
  if (busy()) {
    done({false, "another switch is being applied; retry"});
    return;
  }
  std::vector<std::string> startable, unfit;
  for (const std::string& name : start) {
    const ControllerSlot* s = find(name);
    const std::string why = s && !s->running ? unfit_to_start(*s) : "";
    if (why.empty())
      startable.push_back(name);
    else
      unfit.push_back(why);
  }
  if (!unfit.empty() && strictness == cm_request_t::STRICT) {
    done({false, join(unfit, "; ") + "; nothing was switched"});
    return;
  }
  std::vector<LoadedController> loaded;
  for (const auto& s : loop_.slots()) {
    loaded.push_back({s->name, s->state(), &s->controller->claim(), {}});
    for (const JointData* j : s->claimed)
      if (!j->exported_by.empty()) loaded.back().follows.push_back(j->exported_by);
  }
  SwitchPlan plan = plan_switch(loaded, startable, stop, strictness);
  plan.notes.insert(plan.notes.begin(), unfit.begin(), unfit.end());
  const std::string notes = plan.notes.empty() ? "" : " (" + join(plan.notes, "; ") + ")";
  if (!plan.ok) {
    done({false, plan.message + notes});
    return;
  }
  if (plan.empty()) {
    done({true, "nothing to switch" + notes});
    return;
  }
  std::vector<ControllerSlot*> stop_slots, start_slots;
  std::vector<std::string> stop_names, start_names;
  for (int k : plan.stop) stop_slots.push_back(loop_.slots()[k].get()), stop_names.push_back(loaded[k].name);
  for (int k : plan.start) start_slots.push_back(loop_.slots()[k].get()), start_names.push_back(loaded[k].name);
  pending_summary_ =
      fmt::format("stopped [{}], started [{}]{}", join_some(stop_names, 20), join_some(start_names, 20), notes);
  loop_.set_pending_switch(stop_slots, start_slots);
  pending_component_ = false;
  pending_done_ = std::move(done);
  if (!ticking()) {
    loop_.apply_now();
    pending_summary_ =
        fmt::format("switched at once ({}): {}",
                    loop_.has_state() ? "hardware is silent" : "no hardware state received yet", pending_summary_);
    complete_pending();
  }
}

void ControllerManager::complete_pending() {
  Done done = std::move(pending_done_);
  pending_done_ = nullptr;
  std::string msg = pending_summary_;
  const bool in_cycle = loop_.last_switch_step() >= 0 && msg.rfind("switched at once", 0) != 0;
  if (in_cycle && pending_component_)
    msg = fmt::format("{} at step {} (t={:.6f} s)", msg, loop_.last_switch_step(), loop_.now().seconds());
  else if (in_cycle)
    msg = fmt::format("switched in one cycle at step {} (t={:.6f} s): {}", loop_.last_switch_step(),
                      loop_.now().seconds(), msg);
  msg += take_chain_stops(nullptr);
  std::vector<std::string> refused;
  for (const auto& s : loop_.slots())
    if (std::exchange(s->start_refused, false)) refused.push_back(s->name);
  if (!refused.empty())
    msg += fmt::format("; but not started [{}]: a hardware component they use left the state they need meanwhile",
                       join(refused));
  changed();
  if (done) done({true, msg});
}

void ControllerManager::reload(bool force, Done done) {
  if (shutting_down_) return done({false, kShuttingDown});
  std::vector<std::string> loaded, running;
  for (const auto& s : loop_.slots()) {
    loaded.push_back(s->name);
    if (s->running) running.push_back(s->name);
  }
  if (!loaded.empty() && !force) {
    done({false, fmt::format("cannot reload: {} controller(s) loaded ({}); unload them first or reload with force",
                             loaded.size(), join_some(loaded, 20))});
    return;
  }
  auto read = [this, loaded, done](const Reply& stopped) {
    if (!stopped.ok) {
      done({false, "cannot reload: stopping failed: " + stopped.message});
      return;
    }
    // A copy of the robot without its controllers (thousands of them cost milliseconds to copy), read into off the
    // loop when slicing.
    std::vector<ControllerSpec> keep = std::move(model_.controllers);
    auto keep_files = std::move(model_.config_key_files);
    RobotModel fresh = model_;
    model_.controllers = std::move(keep);
    model_.config_key_files = std::move(keep_files);
    fresh.controllers.clear();
    fresh.config_key_files.clear();
    fresh.pid_gains.clear();
    fresh.config_section.clear();
    fresh.notes.clear();
    fresh.warnings.clear();
    auto parse = [background = options_.slice_us > 0](RobotModel m) {
      if (background) become_background_thread("cm-reload");
      ReadConfig read;
      try {
        load_control_config_into(m, m.config_paths);
        validate(m);
        read.index = index_of(m.controllers);
      } catch (const ModelError& e) {
        read.error = join(e.problems(), "; ");
      }
      read.model = std::move(m);
      return read;
    };
    reload_done_ = done;
    reload_unloaded_ = loaded;
    if (options_.slice_us > 0) {
      reload_read_ = std::async(std::launch::async, parse, std::move(fresh));
      return;
    }
    finish_reload(parse(std::move(fresh)));
  };
  if (running.empty()) {
    read({true, ""});
    return;
  }
  switch_controllers({}, running, cm_request_t::STRICT, read);
}

void ControllerManager::finish_reload(ReadConfig read) {
  run_config_.reset();  // the next publish_config reads what the reload read
  Done done = std::move(reload_done_);
  reload_done_ = nullptr;
  if (!read.error.empty()) {
    done({false, fmt::format("cannot reload: {}; nothing was changed", read.error)});
    return;
  }
  sources_.end_all("controllers reloaded");
  auto& slots = loop_.slots();
  while (!slots.empty()) {
    hw_.set_references_live(slots.back()->name, false);
    retire(std::move(slots.back()));
    slots.pop_back();
  }
  loop_.reorder();
  // Ten thousand entries of one YAML document take 40 ms to free, some single entries several ms (yaml-cpp merges
  // the memory of nodes used together): a worker frees them, in another allocator arena than the loop's (main.cpp
  // reads the first configuration on a thread of its own, a reload reads on one), so the loop's allocations never
  // wait for that arena's lock.
  auto old = std::make_pair(std::exchange(model_.controllers, std::move(read.model.controllers)),
                            std::exchange(model_.config_key_files, std::move(read.model.config_key_files)));
  if (options_.slice_us > 0)
    disposal_ = std::async(std::launch::async, [old = std::move(old)]() mutable {
      become_background_thread("cm-dispose");
      old = {};
    });
  configured_ = std::move(read.index);
  changed();
  done({true, fmt::format("reloaded {}: {} controller(s) configured ({}); unloaded [{}]", model_.config_path,
                          model_.controllers.size(), names_configured(), join_some(reload_unloaded_, 20))});
}

Reply ControllerManager::publish_config() {
  if (!run_config_) {
    const std::string why = read_run_config();
    if (!why.empty()) return {false, "cannot publish the run's configuration: " + why};
  }
  run_config_t& m = *run_config_;
  m.utime = wall_us();
  bus_.lcm().publish(bus_.channel(channels::kCmConfig), &m);
  return {true, fmt::format("published the run's configuration on {} ({} and {} file(s), {} bytes)",
                            bus_.channel(channels::kCmConfig), model_.urdf_path, m.num_configs, m.getEncodedSize())};
}

std::string ControllerManager::read_run_config() {
  run_config_t m;
  const std::string why = lcm_control::read_run_config(model_, "controller_manager", options_.command_line, &m);
  if (why.empty()) run_config_ = std::move(m);
  return why;
}

std::string ControllerManager::type_doc(const std::string& type) const {
  const ControllerTypeInfo* info = registry_.info(type);
  if (!info || info->doc.empty()) return "";
  return fmt::format("{}{}: {}", to_string(info->ros), info->chainable ? ", chainable" : "", info->doc);
}

std::vector<controller_info_t> ControllerManager::list() const {
  return list(std::numeric_limits<size_t>::max());
}

std::vector<controller_info_t> ControllerManager::list(size_t max_bytes) const {
  std::vector<controller_info_t> out;
  size_t bytes = 0;
  for (size_t k = 0; k < loop_.slots().size(); ++k) {
    const ControllerSlot& s = *loop_.slots()[k];
    controller_info_t i;
    i.name = s.name;
    i.type = s.type;
    i.state = s.state();
    const Claim& c = s.controller->claim();
    i.hardware_interface = c.interface ? to_string(*c.interface) : "";
    for (size_t j = 0; c.interface && j < c.joints.size(); ++j)  // a drive's wheels and steering: each interface
      if (i.hardware_interface.find(to_string(c.interface_of(j))) == std::string::npos)
        i.hardware_interface += std::string(", ") + to_string(c.interface_of(j));
    i.joints = c.joints;
    i.num_joints = static_cast<int32_t>(i.joints.size());
    describe_command(registry_.info(s.type), *s.controller, i);
    bytes += static_cast<size_t>(i._getEncodedSizeNoHash());
    if (bytes > max_bytes) break;
    out.push_back(std::move(i));
  }
  return out;
}

std::vector<joint_interfaces_t> ControllerManager::interfaces() const {
  std::vector<joint_interfaces_t> out;
  for (const JointData& j : hw_.joints()) {
    joint_interfaces_t i;
    i.joint = j.name;
    for (Interface x : j.offered) i.command.push_back(quantity_of(x));
    const Ros2Component* c = nullptr;
    for (const HardwareBlock& b : model_.ros2_control)
      if (!c) c = b.joint(j.name);
    if (c)
      for (const Ros2Interface& s : c->state_interfaces) i.state.push_back(s.name);
    else
      i.state = {"position", "velocity", "effort"};
    for (const auto& s : loop_.slots())
      if (s->running && s->controller->claim().interface)
        for (size_t k = 0; k < s->controller->claim().joints.size(); ++k)
          if (s->controller->claim().joints[k] == j.name) {
            i.claimed = quantity_of(s->controller->claim().interface_of(k));
            i.claimed_by = s->name;
          }
    for (const std::string& s : i.state)
      i.state_value.push_back(s == "position" ? j.position : s == "velocity" ? j.velocity : s == "effort" ? j.effort : NAN);
    i.command_value = j.owner ? j.command : NAN;
    i.num_command = static_cast<int32_t>(i.command.size());
    i.num_state = static_cast<int32_t>(i.state.size());
    out.push_back(std::move(i));
  }
  return out;
}

std::string ControllerManager::hardware_summary(int64_t now) const {
  return hw_status_.describe(now, options_.silence_us, bus_.channel(channels::kHardwareState),
                             bus_.hardware_apart() ? "--hardware-url " + bus_.hardware_url() : "LCM URL");
}

void ControllerManager::on_hardware_state(const hardware_state_t& st) {
  const int64_t now = monotonic_us();
  if (hw_.bound() && st.session != hw_.session() && loop_.has_state() && !silent_ &&
      now - last_state_us_ < options_.silence_us) {
    // A second session while the one we follow counts as alive: kept until that one speaks again (two simulators on
    // one namespace: keep following the first) or falls silent (it had ended: a sweep; poll() answers this one).
    ++dropped_;  // counted in controller_manager/statistics
    waiting_ = st;
    has_waiting_ = true;
    return;
  }
  if (has_waiting_ && st.session == hw_.session()) {
    has_waiting_ = false;
    hardware_log_.warn(fmt::format("two hardware sessions publish {}: following {:x}, ignoring {:x} while the first "
                                   "keeps publishing. Two sim_servers on one namespace? Stop one, or give each robot "
                                   "its own --namespace",
                                   bus_.channel(channels::kHardwareState), hw_.session(), waiting_.session));
  }
  last_state_us_ = now;
  if (!hw_.bound() || st.session != hw_.session() || st.num_actuators != command_.num_actuators) {
    const std::string why = hw_.bind(st, command_);
    if (!why.empty()) {
      if (st.session != bad_session_)
        hardware_log_.warn(fmt::format("hardware session {:x}: {}; not answering it", st.session, why));
      bad_session_ = st.session;
      return;
    }
    hardware_log_.info(fmt::format("hardware session {:x}: {} actuators, {}, period {} us, step {}", st.session,
                                   st.num_actuators, st.lockstep ? "lockstep" : "real time", st.period_us, st.step));
  }
  hw_status_.seen(st, now);
  if (ShmLink* shm = bus_.hardware_shm()) shm->yield_first(st.lockstep);
  outbox_.send_here(st.lockstep);
  if (intake_) intake_->set_in_place(st.lockstep);
  if (silent_) {
    silent_ = false;
    // In lockstep, time stands still while nobody answers: the next step of the
    // same session continues where the controllers left off.
    const bool continuous = st.lockstep && st.session == hw_.session() && loop_.has_state() &&
                            (st.step == loop_.step() || st.step == loop_.step() + 1);
    if (continuous) {
      spdlog::info("hardware/state resumed at step {} (lockstep: time did not advance): controllers continue", st.step);
    } else {
      loop_.restart_next_cycle();
      spdlog::info("hardware/state resumed at step {}: running controllers restart from the current state", st.step);
    }
  }
  if (loop_.has_state() && !silent_ && st.session == hw_.session() && st.step < loop_.step())
    hardware_log_.info(fmt::format("hardware step went back from {} to {} (a reset): running controllers restart from "
                                   "the measured state",
                                   loop_.step(), st.step));
  arrivals_.arrived(now, st.lockstep ? 0 : st.period_us);
  inputs_.stamp(st.session, st.step);
  loop_.cycle(st, command_);
  if (st.num_component_errors > 0) report_component_errors(st);
  report_failed_controllers();
  sources_.after_cycle();  // before the command: the echo is on the bus before the next state
  command_pub_.publish(command_);
  if (st.lockstep) outbox_.send_queued();  // after the command: the hardware steps meanwhile when it has a CPU
  if (pending_done_ && !loop_.switch_pending()) complete_pending();
}

void ControllerManager::flush_published() {
  outbox_.flush();
  for (const auto& slot : loop_.slots())
    if (slot->outbox) slot->outbox->flush();
}

void ControllerManager::deliver_held() {
  for (const auto& slot : loop_.slots())
    if (slot->async) slot->endpoints->deliver_held();
}

void ControllerManager::poll(int64_t now) {
  if (outbox_.sends_here()) outbox_.send_queued();  // what a paused lockstep's controllers published meanwhile
  if (intake_) intake_->drain();                     // goals prepared off the loop, taken whole
  deliver_held();
  sources_.poll();
  if (loop_.has_state() && !silent_ && now - last_state_us_ > options_.silence_us) {
    silent_ = true;
    spdlog::warn("no hardware/state for {} ms (last step {}): controllers are not updated until it resumes",
                 (now - last_state_us_) / 1000, loop_.step());
    if (std::exchange(has_waiting_, false)) {
      spdlog::info("answering hardware session {:x}, which began before {:x} counted as silent", waiting_.session,
                   hw_.session());
      on_hardware_state(waiting_);
    }
  }
  if (pending_done_ && !ticking()) {
    loop_.apply_now();
    pending_summary_ = "switched at once (hardware is silent): " + pending_summary_;
    complete_pending();
  }
  if (reload_read_.valid() && reload_read_.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
    finish_reload(reload_read_.get());
  }
  for (const int64_t end = now + options_.slice_us; !retired_.empty() && monotonic_us() < end;) retired_.pop_back();
  if (activity_due_ || now - last_activity_us_ >= 1000000) {
    activity_due_ = false;
    last_activity_us_ = now;
    activity_pub_.publish(activity());
  }
  if (now - last_stats_us_ >= 1000000) {
    last_stats_us_ = now;
    hw_status_.close_window(now);
    stats_pub_.publish(statistics());
  }
}

loop_stats_t ControllerManager::statistics() {
  loop_stats_t m{};
  m.utime = wall_us();
  m.process = "controller_manager";
  loop_.stats().fill_and_reset(m);
  int64_t dropped = dropped_ + bus_.hardware_skipped();
  if (const std::string note = bus_.hardware_loss_note(); !note.empty()) hardware_log_.warn(note);
  for (const auto& s : loop_.slots()) {
    add_item(m, s->name, "controller", s->exec, &s->period);
    dropped += s->controller->dropped();
  }
  m.dropped = std::max<int64_t>(0, dropped - reported_dropped_);
  reported_dropped_ = dropped;
  int64_t unpublished = outbox_.dropped() + bus_.hardware_refused();
  for (const auto& slot : loop_.slots())
    if (slot->outbox) unpublished += slot->outbox->dropped();
  m.unpublished = unpublished - reported_unpublished_;
  reported_unpublished_ = unpublished;
  return m;
}

std::string ControllerManager::shutdown() {
  std::vector<std::string> stopped, unloaded;
  shutting_down_ = true;
  // Answering a pending switch lets the services start the requests that waited for it; those are refused at once.
  while (pending_done_) {
    Done d = std::move(pending_done_);
    pending_done_ = nullptr;
    d({false, kShuttingDown});
  }
  for (const auto& s : loop_.slots()) {
    if (s->running) stopped.push_back(s->name);
    unloaded.push_back(s->name);
  }
  if (reload_read_.valid()) reload_read_.wait();
  reload_read_ = {};
  if (Done d = std::move(reload_done_)) {
    reload_done_ = nullptr;
    d({false, kShuttingDown});
  }
  retired_.clear();
  if (disposal_.valid()) disposal_.wait();
  loop_.cancel_pending();
  sources_.end_all("the controller manager is shutting down");
  sources_.poll();
  loop_.stop_all();
  auto& slots = loop_.slots();
  while (!slots.empty()) slots.pop_back();
  loop_.reorder();
  return fmt::format("stopped [{}], unloaded [{}]", join(stopped), join(unloaded));
}

}  // namespace lcm_control::cm
