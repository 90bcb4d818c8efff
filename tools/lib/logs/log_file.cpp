#include "tools/lib/logs/log_file.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "description/robot_model.hpp"

namespace lcm_control::tools {

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
