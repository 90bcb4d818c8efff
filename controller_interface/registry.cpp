#include "controller_interface/registry.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "description/text.hpp"

namespace lcm_control::cm {

void Registry::add(ControllerType type) {
  const std::string name = type.info.name;
  types_[name] = std::move(type);
}

void Registry::add(const std::string& type, Factory factory) {
  ControllerType t;
  t.info.name = type;
  t.factory = std::move(factory);
  add(std::move(t));
}

void Registry::merge(Registry&& other) {
  for (auto& [n, t] : other.types_) types_[n] = std::move(t);
}

std::unique_ptr<Controller> Registry::create(const std::string& type) const {
  auto it = types_.find(type);
  return it == types_.end() ? nullptr : it->second.factory(type);
}

const ControllerTypeInfo* Registry::info(const std::string& type) const {
  auto it = types_.find(type);
  return it == types_.end() ? nullptr : &it->second.info;
}

std::vector<std::string> Registry::types() const {
  std::vector<std::string> v;
  for (const auto& [t, x] : types_) v.push_back(t);
  return v;
}

std::string Registry::closest(const std::string& type) const {
  std::string best;
  size_t best_d = SIZE_MAX;
  const bool bare = type.find('/') == std::string::npos;
  for (const auto& [t, x] : types_) {
    size_t d = edit_distance(type, t);
    if (bare) d = std::min(d, edit_distance(type, t.substr(t.find('/') + 1)));
    if (d < best_d) best_d = d, best = t;
  }
  return best;
}

bool Registry::misspelling(const std::string& type) const {
  if (types_.empty() || has(type)) return false;
  const std::string near = closest(type);
  const bool bare = type.find('/') == std::string::npos;
  const size_t d = std::min(edit_distance(type, near), bare ? edit_distance(type, near.substr(near.find('/') + 1))
                                                             : edit_distance(type, near));
  return d <= 3 && d * 8 <= type.size();
}

}  // namespace lcm_control::cm
