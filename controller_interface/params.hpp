// A controller's YAML entry, read like ROS's param server under `<controller>/`:
// typed getters whose errors name the file, the controller and the key, and a
// record of which keys were read so unknown keys can be reported.
#pragma once

#include <yaml-cpp/yaml.h>

#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "control/pid.hpp"

namespace lcm_control::cm {

// A controller cannot be loaded; what() is one line saying why.
class ControllerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The URDF's transmissions do not offer the joint or interface the controller claims: the YAML fits another
// variant of the robot (iiwa_stack's YAML has controllers for all three interfaces).
class InterfaceError : public ControllerError {
 public:
  using ControllerError::ControllerError;
};

class Params {
 public:
  // where: "<file>: <controller>" used as the prefix of every message.
  Params(YAML::Node node, std::string where);

  const std::string& where() const { return where_; }
  bool has(const std::string& key) const;
  YAML::Node node(const std::string& key) const;  // marks the key as read

  std::string string(const std::string& key) const;  // required
  double number(const std::string& key) const;       // required
  double number(const std::string& key, double fallback) const;
  bool boolean(const std::string& key, bool fallback) const;
  std::vector<std::string> strings(const std::string& key) const;  // required, non-empty, no duplicates
  // `key: {p, i, d, i_clamp | i_clamp_min/i_clamp_max, antiwindup}`, p required.
  PidGains pid(const std::string& key) const;
  static PidGains pid_from(const YAML::Node& n, const std::string& where);

  // Top-level keys present but never read (type excluded).
  std::vector<std::string> unused() const;

  ControllerError error(const std::string& key, const std::string& problem) const;
  // `key` is missing: `what` it should be, and a key present but unread that is close to it (a misspelling).
  ControllerError missing(const std::string& key, const std::string& what) const;

 private:
  YAML::Node node_;
  std::string where_;
  mutable std::set<std::string> read_;
};

}  // namespace lcm_control::cm
