// Spawning a set of controllers (the spawner program), per controller as ROS's spawners do: load each, and a
// controller that fails to load (or to start) is reported by name with the reason while the others are started
// in one strict switch (--activate-as-group: all or nothing instead). Later stop and unload exactly those, with
// bounded waits. The client may be a new one at teardown.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "tools/lib/clients/cm_client.hpp"

namespace lcm_control::tools {

struct SpawnOptions {
  bool stopped = false;      // load only, do not start
  std::vector<std::string> inactive;  // also loaded, never started (ROS 2: spawned --inactive)
  bool as_group = false;     // all or nothing (ROS 2's --activate-as-group): any failure unloads all and throws
  double timeout_s = 10;     // for the manager to answer at all, and for each request
  std::function<void(const std::string&)> say;  // progress lines (may be empty)
};

// The namespace of a ROS 2 controller manager node name ("/robot1/controller_manager" -> "robot1",
// "controller_manager" -> ""); any other last name is refused (this controller manager is always that one).
std::string ros2_manager_namespace(const std::string& node);

class Spawner {
 public:
  Spawner(std::vector<std::string> names, SpawnOptions options);

  // Loads each controller; one that fails to load or start is recorded in failed() and the others run (ROS 1's
  // controller_manager spawner). Throws std::runtime_error naming the controllers and reasons (or CmTimeout),
  // after unloading whatever it had loaded, when none could be spawned, when the manager stops answering, or on
  // any failure with as_group.
  void spawn(CmClient& cm);

  // Stops what spawn() started (one switch) and unloads what it loaded (reverse
  // order). Gives up at the first unanswered request, so it returns within about
  // timeout_s even when the manager is gone. Returns false if not all went well;
  // never throws.
  bool teardown(CmClient& cm, double timeout_s);

  const std::vector<std::string>& loaded() const { return loaded_; }
  bool started() const { return !running_.empty(); }
  const std::vector<std::string>& running() const { return running_; }
  // The controllers that could not be spawned: name, and why ("failed to load: ..." / "could not start: ...").
  const std::vector<std::pair<std::string, std::string>>& failed() const { return failed_; }

 private:
  void say(const std::string& line) const;
  void start(CmClient& cm, const std::vector<std::string>& names);

  std::vector<std::string> names_;
  SpawnOptions o_;
  std::vector<std::string> loaded_;
  std::vector<std::string> running_;  // those of names_ it started
  std::vector<std::pair<std::string, std::string>> failed_;
};

}  // namespace lcm_control::tools
