#include "bus/digest.hpp"

#include <cstring>

namespace lcm_control {

namespace {
// Mixes `size` bytes into `h`, eight at a time (the tail byte by byte).
uint64_t mix(uint64_t h, const uint8_t* p, size_t size) {
  constexpr uint64_t kPrime = 0x100000001b3ull;
  size_t k = 0;
  for (; k + 8 <= size; k += 8) {
    uint64_t w;
    std::memcpy(&w, p + k, 8);
    h = (h ^ w) * kPrime;
    h ^= h >> 29;
  }
  for (; k < size; ++k) h = (h ^ p[k]) * kPrime;
  return h;
}
}  // namespace

uint64_t message_digest(const void* data, size_t size) {
  using namespace digest;
  const auto* p = static_cast<const uint8_t*>(data);
  const uint64_t n = size;
  uint64_t h = mix(0xcbf29ce484222325ull, reinterpret_cast<const uint8_t*>(&n), sizeof n);
  if (size <= kWholeBytes) return mix(h, p, size);
  h = mix(h, p, kEndBytes);
  for (size_t k = 0; k < kSamples; ++k) h = mix(h, p + sample_at(size, k), kSampleBytes);
  return mix(h, p + size - kEndBytes, kEndBytes);
}

}  // namespace lcm_control
