// Logging setup shared by every program: one line per message, prefixed with
// the program name, to stderr. Never call it on a real-time path.
#pragma once

#include <spdlog/spdlog.h>

#include <string>

namespace lcm_control {

// level: "debug", "info", "warn", "error" (default info, or LCM_CONTROL_LOG_LEVEL).
void setup_logging(const std::string& program, const std::string& level = "");

}  // namespace lcm_control
