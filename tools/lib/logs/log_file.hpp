// An lcm-logger log (bus record's too) opened for reading, or refused naming the file; and read event by event fast.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace lcm_control::tools {

// A path that is not a readable regular file, or not a log, is a ModelError (exit code 3) naming it.
std::unique_ptr<lcm::LogFile> open_log(const std::string& path);

// A log read in order as liblcm reads it (a sync word, skipping what is not one; the header; a channel name of 1 to
// 999 bytes; the data, followed by the next sync word or the end of the file; an event not whole ends the log),
// through a large buffer and into rooms reused from event to event: no allocation and no system call per event
// (lcm::LogFile seeks back after checking each event's next sync word).
class LogReader {
 public:
  explicit LogReader(const std::string& path);
  ~LogReader();
  LogReader(const LogReader&) = delete;
  LogReader& operator=(const LogReader&) = delete;
  bool good() const { return file_ != nullptr; }
  // The next event, valid until the next call; nullptr at the end of what is whole.
  const lcm::LogEvent* next();
  // The byte after the last event read whole.
  int64_t end_of_whole() const { return end_; }

 private:
  std::FILE* file_ = nullptr;
  lcm::LogEvent event_{};
  std::vector<uint8_t> data_;
  int64_t offset_ = 0, end_ = 0, size_ = -1;  // size_: the file's, as opened
  bool synced_ = false;                       // the next event's sync word is read already
};

}  // namespace lcm_control::tools
