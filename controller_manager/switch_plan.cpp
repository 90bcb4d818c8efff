#include "controller_manager/switch_plan.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include "controller_interface/claims.hpp"
#include "description/text.hpp"
#include "rt/log.hpp"
#include "lcm_control/cm_request_t.hpp"

namespace lcm_control::cm {

namespace {
std::string names_of(const std::vector<LoadedController>& loaded) {
  if (loaded.empty()) return "none";
  std::vector<std::string> v;
  for (const auto& c : loaded) v.push_back(c.name);
  return join_some(v, 20);
}
// One note for every name of a best-effort switch that is not loaded, however many: the first few, clipped.
std::string not_loaded_note(const char* verb, const std::vector<std::string>& unknown,
                            const std::vector<LoadedController>& loaded) {
  std::vector<std::string> quoted;
  for (const auto& n : unknown) quoted.push_back("'" + clip(n, 60) + "'");
  return fmt::format("ignored: cannot {} {}: not loaded (loaded: {})", verb, join_some(quoted, 5), names_of(loaded));
}
}  // namespace

SwitchPlan plan_switch(const std::vector<LoadedController>& loaded, const std::vector<std::string>& start,
                       const std::vector<std::string>& stop, int strictness) {
  SwitchPlan plan;
  auto refuse = [&](std::string why) {
    plan.ok = false;
    plan.message = std::move(why);
    plan.start.clear();
    plan.stop.clear();
    return plan;
  };
  if (strictness == 0) {
    plan.notes.push_back("strictness 0 treated as BEST_EFFORT");
    strictness = cm_request_t::BEST_EFFORT;
  }
  if (strictness != cm_request_t::BEST_EFFORT && strictness != cm_request_t::STRICT)
    return refuse(fmt::format("strictness {} is neither 1 (BEST_EFFORT) nor 2 (STRICT)", strictness));
  const bool strict = strictness == cm_request_t::STRICT;
  // Hashed: a thousand names against a thousand loaded controllers, between two cycles.
  const std::unordered_set<std::string_view> stopping(stop.begin(), stop.end());
  for (const auto& s : start)
    if (stopping.count(s)) return refuse(fmt::format("'{}' is in both the start and the stop list", clip(s)));
  std::unordered_map<std::string_view, int> index;
  for (size_t k = 0; k < loaded.size(); ++k) index.emplace(loaded[k].name, static_cast<int>(k));
  auto index_of = [&](const std::string& n) {
    const auto it = index.find(n);
    return it == index.end() ? -1 : it->second;
  };
  std::vector<bool> in_stop(loaded.size()), in_start(loaded.size());

  // The loaded controllers `names` asks to start (`starting`) or stop: an unknown one is noted (BEST_EFFORT) or
  // refuses the switch (STRICT), as one already in the state asked for does. "" or the refusal.
  auto pick = [&](const std::vector<std::string>& names, bool starting, std::vector<int>& picked,
                  std::vector<bool>& in) -> std::string {
    const char* verb = starting ? "start" : "stop";
    std::vector<std::string> unknown;
    for (const auto& n : names) {
      const int k = index_of(n);
      std::string why;
      if (k < 0 && !strict) {
        unknown.push_back(n);
        continue;
      }
      if (k < 0)
        why = fmt::format("cannot {} '{}': it is not loaded (loaded: {})", verb, clip(n), names_of(loaded));
      else if (starting && loaded[k].state == "running")
        why = fmt::format("cannot start '{}': it is already running", n);
      else if (!starting && loaded[k].state != "running")
        why = fmt::format("cannot stop '{}': it is not running (state: {})", n, loaded[k].state);
      if (!why.empty()) {
        if (strict) return why + " [STRICT]";
        plan.notes.push_back("ignored: " + why);
        continue;
      }
      if (!in[size_t(k)]) picked.push_back(k), in[size_t(k)] = true;
    }
    if (!unknown.empty()) plan.notes.push_back(not_loaded_note(verb, unknown, loaded));
    return "";
  };
  if (const std::string why = pick(stop, false, plan.stop, in_stop); !why.empty()) return refuse(why);
  if (const std::string why = pick(start, true, plan.start, in_start); !why.empty()) return refuse(why);
  std::sort(plan.stop.begin(), plan.stop.end());
  std::sort(plan.start.begin(), plan.start.end());

  // The set running after the switch: controllers kept first, then the started ones.
  std::vector<std::pair<std::string, const Claim*>> after;
  for (size_t k = 0; k < loaded.size(); ++k)
    if (loaded[k].state == "running" && !in_stop[k])
      after.emplace_back(loaded[k].name, loaded[k].claim);
  for (int k : plan.start) after.emplace_back(loaded[k].name, loaded[k].claim);
  if (auto c = find_conflict(after))
    return refuse("cannot switch: " + c->message() + " (claim conflicts are refused whatever the strictness)");
  // Chaining: whoever writes a controller's reference interfaces runs only while that controller runs.
  std::unordered_set<std::string_view> running_after;
  for (const auto& [name, claim] : after) running_after.insert(name);
  for (size_t k = 0; k < loaded.size(); ++k) {
    if (!running_after.count(loaded[k].name)) continue;
    for (const std::string& f : loaded[k].follows) {
      if (running_after.count(f)) continue;
      const int fk = index_of(f);
      if (in_start[k])
        return refuse(fmt::format("cannot start '{}': it writes the reference interfaces of '{}', which would not be "
                                  "running; start '{}' too (a chain's followers run first)",
                                  loaded[k].name, f, f));
      return refuse(fmt::format("cannot {} '{}': '{}' writes its reference interfaces and would keep running; stop "
                                "'{}' too",
                                fk >= 0 && in_stop[size_t(fk)] ? "stop" : "leave stopped", f, loaded[k].name,
                                loaded[k].name));
    }
  }
  plan.ok = true;
  return plan;
}

}  // namespace lcm_control::cm
