// A message's bytes summed up in 64 bits, to tell recorded messages apart (which log event a stamp or an echo
// means), not for security. Every byte of a message up to kWholeBytes; past it, the size, the first and last
// kEndBytes and kSampleBytes of every kStride between, so that a 4 MiB trajectory goal costs tens of µs on the
// thread that reads it. Two messages that differ only outside the sampled bytes have the same digest.
#pragma once

#include <cstddef>
#include <cstdint>

namespace lcm_control {

// How much of a message the digest reads.
namespace digest {
inline constexpr size_t kWholeBytes = 64u << 10, kEndBytes = 8u << 10, kStride = 4096, kSampleBytes = 64;
}

uint64_t message_digest(const void* data, size_t size);

}  // namespace lcm_control
