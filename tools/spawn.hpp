// Spawning a set of controllers as one unit, for the spawner program and launch:
// load each, start them all in ONE strict switch, and later stop and unload
// exactly those, with bounded waits.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tools/cm_client.hpp"

namespace lcm_control::tools {

struct SpawnOptions {
  bool stopped = false;      // load only, do not start
  double timeout_s = 10;     // for the manager to answer at all, and for each request
  std::function<void(const std::string&)> say;  // progress lines (may be empty)
};

class Spawner {
 public:
  Spawner(CmClient& cm, std::vector<std::string> names, SpawnOptions options);

  // Throws std::runtime_error "controller 'NAME': REASON" (or CmTimeout) on the
  // first failure, after unloading whatever it had loaded: never half-spawned.
  void spawn();

  // Stops what spawn() started (one switch) and unloads what it loaded (reverse
  // order). Gives up at the first unanswered request, so it returns within about
  // timeout_s even when the manager is gone. Returns false if not all went well;
  // never throws.
  bool teardown(double timeout_s);

  const std::vector<std::string>& loaded() const { return loaded_; }
  bool started() const { return started_; }

 private:
  void say(const std::string& line) const;

  CmClient& cm_;
  std::vector<std::string> names_;
  SpawnOptions o_;
  std::vector<std::string> loaded_;
  bool started_ = false;
};

}  // namespace lcm_control::tools
