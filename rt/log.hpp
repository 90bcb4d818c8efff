// Logging setup shared by every program: one line per message, prefixed with
// the program name, to stderr. Never call it on a real-time path.
#pragma once

#include <spdlog/spdlog.h>

#include <cstdint>
#include <string>
#include <string_view>

#include "rt/escape.hpp"  // every log line goes through escape_controls

namespace lcm_control {

// level: "debug", "info", "warn", "error" (default info, or LCM_CONTROL_LOG_LEVEL).
void setup_logging(const std::string& program, const std::string& level = "");

// `s` escaped (no newline kept) if it has at most max_chars characters, else its start and "... (N bytes)": strings
// from the bus or a file in log lines and answers.
std::string clip(const std::string& s, size_t max_chars = 80);

// Log lines about what arrives on the bus, where anyone may send anything as often as they like: every line is
// clipped to max_chars, and at most `per_second` lines are written each second; the others are counted and the
// count is told with the next line written, so a flood cannot fill the disk. A line the same as the last one written
// is written again only after `repeat_us` (10 s), with how many times it came meanwhile.
class BusLog {
 public:
  explicit BusLog(int per_second = 20, size_t max_chars = 400, int64_t repeat_us = 10000000)
      : per_second_(per_second), max_chars_(max_chars), repeat_us_(repeat_us) {}
  void debug(const std::string& line) { write(spdlog::level::debug, line); }
  void info(const std::string& line) { write(spdlog::level::info, line); }
  void warn(const std::string& line) { write(spdlog::level::warn, line); }
  int64_t suppressed() const { return suppressed_total_; }

 private:
  void write(spdlog::level::level_enum level, const std::string& line);
  int per_second_;
  size_t max_chars_;
  int64_t repeat_us_;
  std::string last_;  // the last line written, clipped
  int64_t last_us_ = -1, repeats_ = 0;
  int64_t window_us_ = -1, suppressed_ = 0, suppressed_total_ = 0;
  int in_window_ = 0;
};

}  // namespace lcm_control
