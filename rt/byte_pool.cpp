#include "rt/byte_pool.hpp"

#include <algorithm>
#include <utility>

namespace lcm_control {

BytePool::BytePool(size_t slots) : kept_(std::max<size_t>(slots, 1)) {}

namespace {
// Puts `mine` in place of the smallest kept room when it is larger; what is let go ends in `mine`.
void keep_larger(std::vector<std::vector<uint8_t>>& kept, std::vector<uint8_t>& mine) {
  mine.clear();
  auto smallest = std::min_element(kept.begin(), kept.end(), [](const auto& a, const auto& b) {
    return a.capacity() < b.capacity();
  });
  if (smallest->capacity() < mine.capacity()) smallest->swap(mine);
}
}  // namespace

void BytePool::give_back(std::vector<uint8_t>&& bytes) {
  std::vector<uint8_t> mine = std::move(bytes);  // freed after the lock is released
  std::lock_guard<std::mutex> lock(mutex_);
  keep_larger(kept_, mine);
}

bool BytePool::offer(std::vector<uint8_t>& bytes) {
  std::vector<uint8_t> mine;
  {
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock()) return false;
    mine.swap(bytes);
    keep_larger(kept_, mine);
  }
  return true;
}

std::vector<uint8_t> BytePool::take(size_t size) {
  std::vector<uint8_t> got;
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return got;
  std::vector<uint8_t>* best = nullptr;  // the smallest that holds `size`
  for (auto& k : kept_)
    if (k.capacity() >= size && (!best || k.capacity() < best->capacity())) best = &k;
  if (best) got.swap(*best);
  return got;
}

size_t BytePool::kept_bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  size_t bytes = 0;
  for (const auto& k : kept_) bytes += k.capacity();
  return bytes;
}

}  // namespace lcm_control
