#include "common/log.hpp"

#include <spdlog/sinks/stdout_color_sinks.h>

#include <cstdlib>

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

}  // namespace lcm_control
