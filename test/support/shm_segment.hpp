// A hardware loop segment (bus/shm_link.hpp) mapped as a hostile process would map it, for tests that write into it
// behind ShmLink's back: a sequence left odd, a size past the slot, a reader place rewritten, the file truncated.
#pragma once

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace lcm_control::testing {

class MappedSegment {
 public:
  explicit MappedSegment(const std::string& path) : fd_(open(path.c_str(), O_RDWR)) {
    struct stat st {};
    if (fd_ >= 0 && fstat(fd_, &st) == 0) size_ = size_t(st.st_size);
    if (size_ > 0) map_ = mmap(nullptr, size_, PROT_READ | PROT_WRITE, MAP_SHARED, fd_, 0);
    if (map_ == MAP_FAILED) map_ = nullptr;
  }
  ~MappedSegment() {
    if (map_) munmap(map_, size_);
    if (fd_ >= 0) close(fd_);
  }
  MappedSegment(const MappedSegment&) = delete;
  MappedSegment& operator=(const MappedSegment&) = delete;

  bool ok() const { return map_ != nullptr; }
  // The header's 32-bit words (the first 16 KiB).
  uint32_t* words() const { return static_cast<uint32_t*>(map_); }
  static constexpr int kHeaderWords = 4096;
  // The index of the size word of the slot named `channel`: a slot header is {named = 1, sequence, size, writer,
  // channel name} in 32-bit words, 64-byte aligned. -1 if no slot has that name.
  int size_word(const std::string& channel) const {
    const uint32_t* w = words();
    for (int k = 0; k + 4 + int(channel.size() / 4) + 1 < kHeaderWords; k += 16)
      if (w[k] == 1 && std::strncmp(reinterpret_cast<const char*>(&w[k + 4]), channel.c_str(), channel.size() + 1) == 0)
        return k + 2;
    return -1;
  }
  // The indices of reader place p's pid and slot mask words: the places follow a 64-byte block of magic, sizes and the
  // naming lock, 64 bytes each, {pid, doorbell, waiting, mask, ...}.
  static int reader_pid_word(int p) { return 16 + 16 * p; }
  static int reader_mask_word(int p) { return 16 + 16 * p + 3; }
  // Cuts the file to `bytes`, as another process of the user could.
  bool truncate(off_t bytes) const { return ftruncate(fd_, bytes) == 0; }
  // The index of that slot's sequence word (odd while a writer is in it, +2 for each whole write), or -1.
  int sequence_word(const std::string& channel) const {
    const int size = size_word(channel);
    return size < 0 ? -1 : size - 1;
  }

 private:
  int fd_ = -1;
  size_t size_ = 0;
  void* map_ = nullptr;
};

}  // namespace lcm_control::testing
