// The processor's internal error: a message without a location, which the processor completes with the file:line
// of the node it was working on and the chain of macro calls and includes (into an XacroError).
#pragma once

#include <stdexcept>
#include <string>

namespace lcm_control::xacro {

class ProcessError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace lcm_control::xacro
