#include "description/initial_positions.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "description/substitution.hpp"
#include "description/text.hpp"

namespace lcm_control {

std::pair<std::string, double> parse_initial_position(const std::string& assignment) {
  const auto [name, text] = parse_arg(assignment);
  double value = 0;
  if (!parse_double(text, value))
    throw std::invalid_argument(fmt::format("initial position '{}': '{}' is not a number; write JOINT=VALUE in rad "
                                            "(or m), e.g. {}=-1.57",
                                            assignment, text, name));
  return {name, value};
}

std::string initial_position_problem(const std::string& assignment) {
  try {
    parse_initial_position(assignment);
    return "";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

}  // namespace lcm_control
