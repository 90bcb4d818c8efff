// Spawning a set of controllers as one unit (the spawner program): load each,
// start them all in ONE strict switch, and later stop and unload exactly
// those, with bounded waits. The client may be a new one at teardown.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tools/lib/cm_client.hpp"

namespace lcm_control::tools {

struct SpawnOptions {
  bool stopped = false;      // load only, do not start
  std::vector<std::string> inactive;  // also loaded, never started (ROS 2: spawned --inactive)
  double timeout_s = 10;     // for the manager to answer at all, and for each request
  std::function<void(const std::string&)> say;  // progress lines (may be empty)
};

// The namespace of a ROS 2 controller manager node name ("/robot1/controller_manager" -> "robot1",
// "controller_manager" -> ""); any other last name is refused (this controller manager is always that one).
std::string ros2_manager_namespace(const std::string& node);

class Spawner {
 public:
  Spawner(std::vector<std::string> names, SpawnOptions options);

  // Throws std::runtime_error "controller 'NAME': REASON" (or CmTimeout) on the
  // first failure, after unloading whatever it had loaded: never half-spawned.
  void spawn(CmClient& cm);

  // Stops what spawn() started (one switch) and unloads what it loaded (reverse
  // order). Gives up at the first unanswered request, so it returns within about
  // timeout_s even when the manager is gone. Returns false if not all went well;
  // never throws.
  bool teardown(CmClient& cm, double timeout_s);

  const std::vector<std::string>& loaded() const { return loaded_; }
  bool started() const { return started_; }

 private:
  void say(const std::string& line) const;

  std::vector<std::string> names_;
  SpawnOptions o_;
  std::vector<std::string> loaded_;
  bool started_ = false;  // names_ run
};

}  // namespace lcm_control::tools
