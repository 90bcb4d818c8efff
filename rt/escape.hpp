// Text that came from outside (the bus, a file, a user) made safe to print on one line: its control characters as
// escapes. The one escaping rule of the project: log lines, quoted YAML scalars in `bus echo`, Python reprs in xacro.
#pragma once

#include <string>
#include <string_view>

namespace lcm_control {

// `s` with its control characters written as escapes (\n, \r, \t, else \xNN, and \x7f) and each character of
// `backslashed` (a quote, the backslash) preceded by a backslash; keep_newlines: a newline stays, followed by two
// spaces, so it continues the line before and never starts one of its own.
std::string escape_controls(std::string_view s, bool keep_newlines = false, std::string_view backslashed = {});

}  // namespace lcm_control
