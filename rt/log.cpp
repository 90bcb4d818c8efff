#include "rt/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <cstdlib>

#include "rt/clock.hpp"

namespace lcm_control {

void setup_logging(const std::string& program, const std::string& level) {
  auto logger = spdlog::stderr_color_mt(program);
  logger->set_pattern("[%n] %^%l%$: %v");
  std::string lvl = level;
  if (lvl.empty())
    if (const char* env = std::getenv("LCM_CONTROL_LOG_LEVEL")) lvl = env;
  logger->set_level(lvl.empty() ? spdlog::level::info : spdlog::level::from_str(lvl));
  logger->flush_on(spdlog::level::trace);
  spdlog::set_default_logger(logger);
}

std::string clip(const std::string& s, size_t max_chars) {
  if (s.size() <= max_chars) return s;
  return s.substr(0, max_chars) + "... (" + std::to_string(s.size()) + " bytes)";
}

void BusLog::write(spdlog::level::level_enum level, const std::string& line) {
  if (!spdlog::should_log(level)) return;  // a line not shown does not use up the second's budget
  const int64_t now = monotonic_us();
  if (window_us_ < 0 || now - window_us_ >= 1000000) {
    window_us_ = now;
    in_window_ = 0;
  }
  if (in_window_ >= per_second_) {
    ++suppressed_;
    ++suppressed_total_;
    return;
  }
  ++in_window_;
  if (suppressed_ > 0) {
    spdlog::log(level, "{} ({} similar lines not logged)", clip(line, max_chars_), suppressed_);
    suppressed_ = 0;
  } else {
    spdlog::log(level, "{}", clip(line, max_chars_));
  }
}

}  // namespace lcm_control
