#include "tools/lib/logs/log_file.hpp"

#include <fmt/format.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <utility>

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

LogReader::LogReader(const std::string& path) : file_(std::fopen(path.c_str(), "rb")) {
  struct stat st {};
  if (!file_) return;
  std::setvbuf(file_, nullptr, _IOFBF, 1 << 20);
  if (fstat(fileno(file_), &st) == 0) size_ = int64_t(st.st_size);
}

LogReader::~LogReader() {
  if (file_) std::fclose(file_);
}

namespace {
int64_t big_endian(const uint8_t* b, int bytes) {
  uint64_t v = 0;
  for (int k = 0; k < bytes; ++k) v = (v << 8) | b[k];
  return bytes == 4 ? int64_t(int32_t(uint32_t(v))) : int64_t(v);
}
}  // namespace

const lcm::LogEvent* LogReader::next() {
  if (!file_) return nullptr;
  constexpr uint32_t kSync = 0xEDA1DA01u;
  uint32_t sync = std::exchange(synced_, false) ? kSync : 0;  // the sync word read after the last event
  while (sync != kSync) {
    const int c = getc_unlocked(file_);
    if (c == EOF) return nullptr;
    ++offset_;
    sync = (sync << 8) | uint32_t(c);
  }
  uint8_t header[24];
  if (std::fread(header, 1, sizeof header, file_) != sizeof header) return nullptr;
  offset_ += sizeof header;
  const int64_t channel_length = big_endian(header + 16, 4), data_length = big_endian(header + 20, 4);
  if (channel_length <= 0 || channel_length >= 1000 || data_length < 0) return nullptr;
  if (size_ >= 0 && offset_ + channel_length + data_length > size_) return nullptr;  // torn, or a garbled length
  event_.eventnum = big_endian(header, 8);
  event_.timestamp = big_endian(header + 8, 8);
  event_.datalen = int32_t(data_length);
  event_.channel.resize(size_t(channel_length));
  data_.resize(size_t(data_length));
  if (std::fread(event_.channel.data(), 1, size_t(channel_length), file_) != size_t(channel_length) ||
      std::fread(data_.data(), 1, size_t(data_length), file_) != size_t(data_length))
    return nullptr;
  offset_ += channel_length + data_length;
  // Whole only when the next sync word or the end of the file follows it (liblcm's "Invalid header after log
  // data"): an event whose lengths were garbled ends the log here, as lcm::LogFile ends it.
  if (offset_ != size_) {
    uint8_t next[4];
    if (std::fread(next, 1, 4, file_) != 4 || uint32_t(big_endian(next, 4)) != kSync) return nullptr;
    synced_ = true;
  }
  end_ = offset_;
  if (synced_) offset_ += 4;
  event_.data = data_.data();
  return &event_;
}

}  // namespace lcm_control::tools
