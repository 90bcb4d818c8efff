// What the bus throws when a URL, a channel pattern or a transport cannot be used: one line naming it and the fix.
#pragma once

#include <stdexcept>

namespace lcm_control {

class BusError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lcm_control
