#include "tools/lib/spawn.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <set>

#include "tools/lib/support.hpp"

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
  try {
    cm.wait_for_manager(o_.timeout_s, [&] {
      say(fmt::format("waiting up to {} for the controller manager on '{}'", seconds_text(o_.timeout_s),
                      cm.request_channel()));
    });
    for (const auto& n : all) {
      const cm_response_t r = cm.load({n}, o_.timeout_s);
      if (!r.ok) throw std::runtime_error(fmt::format("controller '{}' failed to load: {}", n, r.message));
      loaded_.push_back(n);
      say(fmt::format("loaded {}", n));
    }
    if (o_.stopped || names_.empty()) return;
    const cm_response_t r = cm.switch_controllers(names_, {}, true, o_.timeout_s);
    if (!r.ok)
      throw std::runtime_error(fmt::format("could not start [{}] (one strict switch, so none started): {}",
                                           fmt::join(names_, ", "), r.message));
    started_ = true;
    say(fmt::format("started {}", fmt::join(names_, ", ")));
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
    if (started_) {
      const cm_response_t r = cm.switch_controllers({}, names_, true, left());
      if (!r.ok) {
        say(fmt::format("stopping [{}] was refused: {}", fmt::join(names_, ", "), r.message));
        all_ok = false;
      }
      started_ = false;
    }
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
    started_ = false;
    return false;
  }
  return all_ok;
}

}  // namespace lcm_control::tools
