#include "tools/lib/launch/spawn.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <set>

#include "rt/stop_signal.hpp"
#include "tools/lib/messages/names.hpp"

namespace lcm_control::tools {

std::string ros2_manager_namespace(const std::string& node) {
  std::string n = node;
  while (!n.empty() && n.back() == '/') n.pop_back();
  const auto slash = n.rfind('/');
  const std::string last = slash == std::string::npos ? n : n.substr(slash + 1);
  if (last != "controller_manager")
    throw std::runtime_error(fmt::format("--controller-manager {}: the node here is always 'controller_manager' "
                                         "(give /NAMESPACE/controller_manager, or --namespace)",
                                         node));
  std::string ns = slash == std::string::npos ? "" : n.substr(0, slash);
  while (!ns.empty() && ns.front() == '/') ns.erase(0, 1);
  return ns;
}


Spawner::Spawner(std::vector<std::string> names, SpawnOptions options)
    : names_(std::move(names)), o_(std::move(options)) {}

void Spawner::say(const std::string& line) const {
  if (o_.say) o_.say(line);
}

void Spawner::spawn(CmClient& cm) {
  std::set<std::string> unique;
  std::vector<std::string> all = names_;
  all.insert(all.end(), o_.inactive.begin(), o_.inactive.end());
  for (const auto& n : all)
    if (!unique.insert(n).second) throw std::runtime_error(fmt::format("controller '{}' is named twice", n));
  auto failures = [&] {
    std::vector<std::string> lines;
    for (const auto& [n, why] : failed_) lines.push_back(fmt::format("controller '{}' {}", n, why));
    return fmt::format("{}", fmt::join(lines, "; "));
  };
  try {
    cm.wait_for_manager(o_.timeout_s, [&] {
      say(fmt::format("waiting up to {} for the controller manager on '{}'", seconds_text(o_.timeout_s),
                      cm.request_channel()));
    });
    for (const auto& n : all) {
      const cm_response_t r = cm.load({n}, o_.timeout_s);
      if (!r.ok) {
        failed_.emplace_back(n, "failed to load: " + r.message);
        if (o_.as_group) throw std::runtime_error(failures() + " (--activate-as-group: none spawned)");
        say(fmt::format("error: controller '{}' failed to load: {}", n, r.message));
        continue;
      }
      loaded_.push_back(n);
      say(fmt::format("loaded {}", n));
    }
    if (loaded_.empty()) throw std::runtime_error(failures());
    if (o_.stopped) return;
    std::vector<std::string> to_start;
    for (const auto& n : names_)
      if (std::find(loaded_.begin(), loaded_.end(), n) != loaded_.end()) to_start.push_back(n);
    if (to_start.empty()) return;
    const cm_response_t r = cm.switch_controllers(to_start, {}, true, o_.timeout_s);
    if (r.ok) {
      running_ = to_start;
      say(fmt::format("started {}", fmt::join(running_, ", ")));
      return;
    }
    if (o_.as_group)
      throw std::runtime_error(fmt::format("could not start [{}] (--activate-as-group: one strict switch, so none "
                                           "started): {}",
                                           fmt::join(to_start, ", "), r.message));
    // Which one? Start each alone, as ROS 2's spawner activates each controller by itself.
    say(fmt::format("starting [{}] together was refused ({}); starting each alone", fmt::join(to_start, ", "),
                    r.message));
    for (const auto& n : to_start) {
      const cm_response_t one = cm.switch_controllers({n}, {}, true, o_.timeout_s);
      if (one.ok) {
        running_.push_back(n);
        say(fmt::format("started {}", n));
      } else {
        failed_.emplace_back(n, "could not start: " + one.message);
        say(fmt::format("error: controller '{}' could not start: {}", n, one.message));
      }
    }
    if (running_.empty() && o_.inactive.empty()) throw std::runtime_error(failures());
  } catch (const std::exception&) {
    // Undo, even after Ctrl-C (a second one cuts it short); keep the stop request.
    const int sig = clear_stop();
    teardown(cm, std::min(2.0, o_.timeout_s));
    if (sig) request_stop(sig);
    throw;
  }
}

bool Spawner::teardown(CmClient& cm, double timeout_s) {
  if (loaded_.empty()) return true;
  const int64_t end = monotonic_us() + int64_t(timeout_s * 1e6);
  auto left = [&] { return std::max(0.05, double(end - monotonic_us()) / 1e6); };
  bool all_ok = true;
  try {
    // Best effort over everything it loaded: since it started them, the user may have stopped some and started
    // others (a switch); those not running are left as they are.
    const cm_response_t stopped = cm.switch_controllers({}, loaded_, false, left());
    if (!stopped.ok) {
      say(fmt::format("stopping [{}] was refused: {}", fmt::join(loaded_, ", "), stopped.message));
      all_ok = false;
    }
    running_.clear();
    while (!loaded_.empty()) {
      const std::string n = loaded_.back();
      const cm_response_t r = cm.unload({n}, left());
      if (!r.ok) {
        say(fmt::format("unloading {} was refused: {}", n, r.message));
        all_ok = false;
      } else {
        say(fmt::format("unloaded {}", n));
      }
      loaded_.pop_back();
    }
  } catch (const std::exception& e) {
    say(fmt::format("gave up stopping and unloading [{}]: {}", fmt::join(loaded_, ", "), e.what()));
    loaded_.clear();
    running_.clear();
    return false;
  }
  return all_ok;
}

}  // namespace lcm_control::tools
