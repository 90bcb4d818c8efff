#include "tools/lib/support.hpp"

#include <fmt/format.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>
#include <time.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "description/robot_model.hpp"

extern char** environ;

namespace lcm_control::tools {

void sleep_until_us(int64_t deadline_us) {
  // monotonic_us() is steady_clock, which is CLOCK_MONOTONIC on Linux.
  timespec ts{};
  ts.tv_sec = deadline_us / 1000000;
  ts.tv_nsec = (deadline_us % 1000000) * 1000;
  while (!stop_requested()) {
    const int rc = clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr);
    if (rc == 0) return;
    if (rc != EINTR) return;
  }
}

void handle_bus(Bus& bus, int timeout_ms) {
  if (!bus.handle(timeout_ms) && !stop_requested())
    throw std::runtime_error(fmt::format("LCM error while receiving on {}", bus.url()));
}

int64_t new_request_id() {
  static std::mt19937_64 rng{std::random_device{}()};
  return int64_t(rng() >> 1) | 1;
}

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

std::unique_ptr<lcm::LogFile> open_log(const std::string& path) {
  struct stat st {};
  if (stat(path.c_str(), &st) != 0)
    throw ModelError(fmt::format("{}: cannot read the log: {}", path, std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw ModelError(fmt::format("{}: not a regular file; give a log written by lcm-logger", path));
  auto log = std::make_unique<lcm::LogFile>(path, "r");
  if (!log->good()) throw ModelError(fmt::format("{}: cannot open as an LCM log", path));
  return log;
}

}  // namespace lcm_control::tools
