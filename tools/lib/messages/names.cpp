#include "tools/lib/messages/names.hpp"

#include <fmt/format.h>

namespace lcm_control::tools {

std::string seconds_text(double s) { return fmt::format("{:g} s", s); }

std::string without_leading_slashes(std::string name) {
  const size_t first = name.find_first_not_of('/');
  return first == std::string::npos ? std::string() : name.substr(first);
}

std::string regex_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (std::string("\\^$.|?*+()[]{}").find(c) != std::string::npos) out += '\\';
    out += c;
  }
  return out;
}

}  // namespace lcm_control::tools
