// Buffers of large messages used again, so that putting one together on a loop's thread touches no page the kernel
// must first find: the first touch of fresh memory cost 1.4 us at the median and up to 440 us on our CI's virtual
// machines, 15-60 us a page while a 3.6 MB goal arrived. A buffer its reader is done with is given back from any
// thread; the loop's thread takes one without ever waiting. At most `slots` buffers are kept (the largest), each
// with its room and nothing else.
#pragma once

#include <cstddef>
#include <cstdint>
#include <mutex>
#include <vector>

namespace lcm_control {

class BytePool {
 public:
  explicit BytePool(size_t slots = 2);
  // Any thread: keeps `bytes`' room, emptied, in place of the smallest kept one when it is larger; what is not kept
  // is freed here, on the giver's thread.
  void give_back(std::vector<uint8_t>&& bytes);
  // Never waits: as give_back() when the pool is free this instant (true, `bytes` taken, the room it replaces freed
  // here), else false and `bytes` left with the caller.
  bool offer(std::vector<uint8_t>& bytes);
  // Never waits, never allocates, never frees: an empty buffer whose capacity holds `size` bytes, or one without room
  // when none kept does (or the pool is in use by a giver this instant).
  std::vector<uint8_t> take(size_t size);
  size_t kept_bytes() const;  // the room kept, for memory figures

 private:
  mutable std::mutex mutex_;
  std::vector<std::vector<uint8_t>> kept_;  // `slots` entries, an empty one is a free slot
};

}  // namespace lcm_control
