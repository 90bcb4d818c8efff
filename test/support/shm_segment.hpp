// A hardware loop segment (bus/shm_link.hpp) mapped as a hostile process would map it, for tests that write into it
// behind ShmLink's back: a sequence left odd, a size past the slot.
#pragma once

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstddef>
#include <cstdint>
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
  // The index of a slot's size word holding `size`: a slot header is {named = 1, sequence (even, not 0 once
  // written), size, writer, channel}. -1 if none.
  int size_word(uint32_t size) const {
    const uint32_t* w = words();
    for (int k = 1; k + 1 < kHeaderWords; ++k)
      if (w[k + 1] == size && w[k - 1] == 1 && w[k] % 2 == 0 && w[k] > 0) return k + 1;
    return -1;
  }

 private:
  int fd_ = -1;
  size_t size_ = 0;
  void* map_ = nullptr;
};

}  // namespace lcm_control::testing
