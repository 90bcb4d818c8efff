// Python's int(text) and float(text) on a string (what xacro's property literals, macro arguments, conditions and
// $(eval)'s args go through): surrounding whitespace allowed, decimal digits, float's exponent, inf and nan.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace lcm_control::xacro {

std::optional<int64_t> python_int(std::string_view text);  // nullopt: int(text) raises (or overflows int64)
std::optional<double> python_float(std::string_view text);

}  // namespace lcm_control::xacro
