// The answer to one request to the controller manager: done or refused, and a line saying what happened or why.
#pragma once

#include <functional>
#include <string>

namespace lcm_control::cm {

struct Reply {
  bool ok = false;
  std::string message;
};
using Done = std::function<void(const Reply&)>;

}  // namespace lcm_control::cm
