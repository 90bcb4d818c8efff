#include "rt/escape.hpp"

#include <fmt/format.h>

namespace lcm_control {

std::string escape_controls(std::string_view s, bool keep_newlines, std::string_view backslashed) {
  std::string out;
  out.reserve(s.size());
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (backslashed.find(ch) != std::string_view::npos) {
      out += '\\';
      out += ch;
    } else if (c == '\n' && keep_newlines) {
      out += "\n  ";  // a continuation, never a line of its own
    } else if (c == '\n') {
      out += "\\n";
    } else if (c == '\r') {
      out += "\\r";
    } else if (c == '\t') {
      out += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else {
      out += ch;
    }
  }
  return out;
}

}  // namespace lcm_control
