#include "controller_interface/params.hpp"

#include "description/robot_model.hpp"
#include "description/control_config.hpp"
#include "description/text.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

namespace lcm_control::cm {

namespace {
std::string kind(const YAML::Node& n) {
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  return "nothing";
}

double to_number(const YAML::Node& n, const std::string& where) {
  if (!n.IsScalar()) throw ControllerError(fmt::format("{}: expected a number, got {}", where, kind(n)));
  try {
    const double v = n.as<double>();
    if (!std::isfinite(v)) throw YAML::Exception(YAML::Mark::null_mark(), "not finite");
    return v;
  } catch (const YAML::Exception&) {
    throw ControllerError(fmt::format("{}: '{}' is not a finite number", where, n.Scalar()));
  }
}
}  // namespace

Params::Params(YAML::Node node, std::string where) : node_(std::move(node)), where_(std::move(where)) {}

bool Params::has(const std::string& key) const { return node_.IsMap() && node_[key]; }

YAML::Node Params::node(const std::string& key) const {
  read_.insert(key);
  if (!node_.IsMap()) return YAML::Node();
  return node_[key];
}

ControllerError Params::error(const std::string& key, const std::string& problem) const {
  return ControllerError(fmt::format("{}/{}: {}", where_, key, problem));
}

ControllerError Params::missing(const std::string& key, const std::string& what) const {
  std::string near;
  if (node_.IsMap()) {
    std::vector<std::string> present;
    for (const auto& kv : node_)
      if (kv.first.IsScalar() && !read_.count(kv.first.Scalar())) present.push_back(kv.first.Scalar());
    near = closest_name(key, present, std::max<size_t>(2, key.size() / 4));
  }
  return error(key, fmt::format("missing (required){}{}", what.empty() ? "" : ": " + what,
                                near.empty() ? "" : fmt::format("; the file has '{}': did you mean '{}'?", near, key)));
}

std::string Params::string(const std::string& key) const {
  const YAML::Node n = node(key);
  if (!n) throw missing(key, "");
  if (!n.IsScalar() || n.Scalar().empty()) throw error(key, "expected a name, got " + kind(n));
  return n.Scalar();
}

double Params::number(const std::string& key) const {
  const YAML::Node n = node(key);
  if (!n) throw missing(key, "a number");
  return to_number(n, where_ + "/" + key);
}

double Params::number(const std::string& key, double fallback) const {
  const YAML::Node n = node(key);
  if (!n) return fallback;
  return to_number(n, where_ + "/" + key);
}

bool Params::boolean(const std::string& key, bool fallback) const {
  const YAML::Node n = node(key);
  if (!n) return fallback;
  try {
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    throw error(key, "expected true or false, got " + kind(n));
  }
}

std::vector<std::string> Params::strings(const std::string& key) const {
  const YAML::Node n = node(key);
  if (!n) throw missing(key, key.find("joint") != std::string::npos ? "a list of joint names" : "a list of names");
  if (!n.IsSequence() || n.size() == 0) throw error(key, "expected a non-empty list of names, got " + kind(n));
  std::vector<std::string> out;
  for (const auto& e : n) {
    if (!e.IsScalar() || e.Scalar().empty()) throw error(key, "every entry must be a name, got " + kind(e));
    for (const auto& s : out)
      if (s == e.Scalar()) throw error(key, "'" + s + "' is listed twice");
    out.push_back(e.Scalar());
  }
  return out;
}

PidGains Params::pid(const std::string& key) const {
  const YAML::Node n = node(key);
  if (!n) throw missing(key, "a map like {p: 100, i: 0, d: 10, i_clamp: 0}");
  return pid_from(n, where_ + "/" + key);
}

PidGains Params::pid_from(const YAML::Node& n, const std::string& where) {
  std::vector<std::string> problems, warnings;  // the i-without-i_clamp warning is the controller's note
  const PidGains g = lcm_control::parse_pid_gains(n, where, problems, warnings);
  if (!problems.empty()) throw ControllerError(fmt::format("{}", fmt::join(problems, "; ")));
  return g;
}

std::vector<std::string> Params::unused() const {
  std::vector<std::string> out;
  if (!node_.IsMap()) return out;
  for (const auto& kv : node_) {
    const std::string k = kv.first.as<std::string>();
    if (k != "type" && !read_.count(k)) out.push_back(k);
  }
  return out;
}

}  // namespace lcm_control::cm
