#include "rt/log.hpp"

#include <fmt/format.h>
#include <spdlog/details/null_mutex.h>
#include <spdlog/sinks/base_sink.h>
#include <spdlog/sinks/stdout_color_sinks.h>

#include <cstdlib>
#include <memory>
#include <string_view>

#include "rt/clock.hpp"

namespace lcm_control {

std::string clip(const std::string& s, size_t max_chars) {
  if (s.size() <= max_chars) return escape_controls(s, false);
  return escape_controls(std::string_view(s).substr(0, max_chars), false) + "... (" + std::to_string(s.size()) +
         " bytes)";
}

namespace {

bool has_controls(std::string_view s) {
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if ((c < 0x20 && c != '\t') || c == 0x7f) return true;
  }
  return false;
}

// Hands every message to `inner` with its control characters escaped (escape_controls, newlines kept as
// continuations): no text that reaches a log, from the bus, a file or anywhere, can move the cursor, colour the
// terminal or start a line that looks like a program's own.
class EscapingSink final : public spdlog::sinks::base_sink<spdlog::details::null_mutex> {
 public:
  explicit EscapingSink(spdlog::sink_ptr inner) : inner_(std::move(inner)) {}

 protected:
  void sink_it_(const spdlog::details::log_msg& msg) override {
    const std::string_view payload(msg.payload.data(), msg.payload.size());
    if (!has_controls(payload)) return inner_->log(msg);
    const std::string text = escape_controls(payload, true);
    spdlog::details::log_msg copy(msg);
    copy.payload = spdlog::string_view_t(text.data(), text.size());
    inner_->log(copy);
  }
  void flush_() override { inner_->flush(); }
  void set_pattern_(const std::string& pattern) override { inner_->set_pattern(pattern); }
  void set_formatter_(std::unique_ptr<spdlog::formatter> f) override { inner_->set_formatter(std::move(f)); }

 private:
  spdlog::sink_ptr inner_;
};

}  // namespace

void setup_logging(const std::string& program, const std::string& level) {
  auto inner = std::make_shared<spdlog::sinks::stderr_color_sink_mt>();
  auto logger = std::make_shared<spdlog::logger>(program, std::make_shared<EscapingSink>(inner));
  spdlog::register_logger(logger);
  logger->set_pattern("[%n] %^%l%$: %v");
  std::string lvl = level;
  if (lvl.empty())
    if (const char* env = std::getenv("LCM_CONTROL_LOG_LEVEL")) lvl = env;
  logger->set_level(lvl.empty() ? spdlog::level::info : spdlog::level::from_str(lvl));
  logger->flush_on(spdlog::level::trace);
  spdlog::set_default_logger(logger);
}

void BusLog::write(spdlog::level::level_enum level, const std::string& line) {
  if (!spdlog::should_log(level)) return;  // a line not shown does not use up the second's budget
  const int64_t now = monotonic_us();
  std::string text = clip(line, max_chars_);
  if (text == last_ && now - last_us_ < repeat_us_) {
    ++repeats_;
    ++suppressed_total_;
    return;
  }
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
  std::string counts;
  if (repeats_ > 0)
    counts = text == last_ ? fmt::format(" (came {} more times in the last {:.1f} s)", repeats_, (now - last_us_) * 1e-6)
                           : fmt::format(" (the line before came {} more times)", repeats_);
  if (suppressed_ > 0) counts += fmt::format(" ({} similar lines not logged)", suppressed_);
  spdlog::log(level, "{}{}", text, counts);
  suppressed_ = repeats_ = 0;
  last_ = std::move(text);
  last_us_ = now;
}

}  // namespace lcm_control
