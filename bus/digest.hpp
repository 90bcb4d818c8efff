// A message's bytes summed up in 64 bits, to tell recorded messages apart (which log event a stamp or an echo
// means), not for security. Every byte of a message up to kWholeBytes; past it, the size, the first and last
// kEndBytes and kSamples evenly spaced samples of kSampleBytes between, so that a 4 MiB trajectory goal costs ~70
// pages read on the thread that reads it: a sample in every 4 KiB page (900 pages for a 3.6 MB goal) cost 0.45 ms
// of a cycle on our CI's virtual machines, a missed translation per page. Two messages that differ only outside the
// sampled bytes have the same digest (a goal's id and stamp are in its first bytes).
#pragma once

#include <cstddef>
#include <cstdint>

namespace lcm_control {

// How much of a message the digest reads.
namespace digest {
inline constexpr size_t kWholeBytes = 64u << 10, kEndBytes = 8u << 10, kSamples = 64, kSampleBytes = 64;
// Where the k-th sample of a message of `size` bytes (over kWholeBytes) starts.
inline size_t sample_at(size_t size, size_t k) {
  return kEndBytes + k * ((size - 2 * kEndBytes - kSampleBytes) / (kSamples - 1));
}
}  // namespace digest

uint64_t message_digest(const void* data, size_t size);

}  // namespace lcm_control
