#include "controllers/ros2_gains.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "controller_interface/params.hpp"

namespace lcm_control::cm {

namespace {

// The keys of ROS 2's gains.<dof>.
const char* const kGainKeys[] = {"p", "i", "d", "i_clamp", "i_clamp_max", "i_clamp_min", "u_clamp_max",
                                 "u_clamp_min", "angle_wraparound", "normalize_error", "antiwindup",
                                 "antiwindup_strategy", "tracking_time_constant", "error_deadband", "saturation",
                                 "save_i_term", "activate_state_publisher"};

}  // namespace

Ros2Gains read_ros2_gains(const YAML::Node& node, const std::string& where, const std::string& feedforward_key,
                          std::vector<std::string>& notes) {
  if (!node.IsMap())
    throw ControllerError(where + ": expected a map {p, i, d, i_clamp_max, i_clamp_min, u_clamp_max, u_clamp_min, " + feedforward_key +
                                  ", angle_wraparound}");
  for (const auto& kv : node) {
    const std::string key = kv.first.as<std::string>();
    if (key != feedforward_key &&
        std::find_if(std::begin(kGainKeys), std::end(kGainKeys), [&](const char* k) { return key == k; }) ==
            std::end(kGainKeys))
      throw ControllerError(fmt::format("{}/{}: unknown key; valid keys are {}, {}", where, key,
                                        fmt::join(kGainKeys, ", "), feedforward_key));
  }
  Ros2Gains out;
  YAML::Node g = YAML::Clone(node);
  auto take = [&](const char* key, double& value) {
    if (!g[key]) return;
    try {
      value = g[key].as<double>();
    } catch (const YAML::Exception&) {
      throw ControllerError(fmt::format("{}/{}: '{}' is not a number", where, key, g[key].Scalar()));
    }
    if (std::isnan(value)) throw ControllerError(fmt::format("{}/{}: is not a number", where, key));
    g.remove(key);
  };
  take(feedforward_key.c_str(), out.feedforward);
  take("u_clamp_min", out.u_min);
  take("u_clamp_max", out.u_max);
  if (out.u_min > out.u_max)
    throw ControllerError(fmt::format("{}: u_clamp_min {} is above u_clamp_max {}", where, out.u_min, out.u_max));
  if (g["angle_wraparound"]) {
    try {
      out.wraparound = g["angle_wraparound"].as<bool>();
    } catch (const YAML::Exception&) {
      throw ControllerError(
          fmt::format("{}/angle_wraparound: '{}' is not true or false", where, g["angle_wraparound"].Scalar()));
    }
    g.remove("angle_wraparound");
  }
  if (g["antiwindup_strategy"] && g["antiwindup_strategy"].IsScalar() && g["antiwindup_strategy"].Scalar() != "none")
    notes.push_back(fmt::format("{}/antiwindup_strategy: '{}' is not implemented; the integral term is clamped to "
                                "i_clamp_min/max",
                                where, g["antiwindup_strategy"].Scalar()));
  g.remove("antiwindup_strategy");
  std::vector<std::string> unsupported;  // control_toolbox keys given and not implemented: named, not dropped silently
  for (const char* key : {"tracking_time_constant", "error_deadband", "save_i_term", "activate_state_publisher",
                          "normalize_error", "saturation"})
    if (g[key]) {
      unsupported.push_back(key);
      g.remove(key);
    }
  if (!unsupported.empty())
    notes.push_back(fmt::format("{}: {}: known ROS 2 gain key{} (control_toolbox), not supported yet; ignored", where,
                                fmt::join(unsupported, ", "), unsupported.size() == 1 ? "" : "s"));
  // ROS 2's i_clamp defaults are infinite; here a clamp of 0 would zero the I term, so "none" is the largest number.
  constexpr double kBig = std::numeric_limits<double>::max();
  auto clamp_or_big = [&](const char* key, double big) {
    if (!g[key]) return;
    try {
      if (std::isinf(g[key].as<double>())) g[key] = big;
    } catch (const YAML::Exception&) {
    }  // pid_from names it
  };
  clamp_or_big("i_clamp_max", kBig);
  clamp_or_big("i_clamp_min", -kBig);
  const bool has_max = g["i_clamp_max"] || g["i_clamp"], has_min = g["i_clamp_min"] || g["i_clamp"];
  if (!g["p"]) g["p"] = 0.0;
  out.pid = Params::pid_from(g, where);
  if (!has_max) out.pid.i_clamp_max = kBig;
  if (!has_min) out.pid.i_clamp_min = -kBig;
  return out;
}

}  // namespace lcm_control::cm
