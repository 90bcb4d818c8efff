// An lcm-logger log (bus record's too) opened for reading, or refused naming the file.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <memory>
#include <string>

namespace lcm_control::tools {

// A path that is not a readable regular file, or not a log, is a ModelError (exit code 3) naming it.
std::unique_ptr<lcm::LogFile> open_log(const std::string& path);

}  // namespace lcm_control::tools
