// bus/digest: what tells recorded messages apart (the controller manager's input stamps, command sources' echoes).
#include <gtest/gtest.h>

#include <vector>

#include "bus/digest.hpp"

using namespace lcm_control;
using namespace lcm_control::digest;

TEST(MessageDigest, EveryByteOfASmallMessageCountsAndItsSize) {
  std::vector<uint8_t> m(1000, 7);
  const uint64_t d = message_digest(m.data(), m.size());
  EXPECT_EQ(d, message_digest(std::vector<uint8_t>(m).data(), m.size()));  // the bytes, not where they are
  for (size_t at : {size_t{0}, size_t{499}, size_t{999}}) {
    std::vector<uint8_t> other = m;
    other[at] ^= 1;
    EXPECT_NE(message_digest(other.data(), other.size()), d) << "byte " << at;
  }
  EXPECT_NE(message_digest(m.data(), m.size() - 1), d);
  EXPECT_NE(message_digest(m.data(), 0), message_digest(m.data(), 1));
}

// Past kWholeBytes: the size, both ends whole and kSamples samples between, the last ending where the end begins.
TEST(MessageDigest, ALargeMessageCountsItsSizeItsEndsAndEvenlySpacedSamples) {
  std::vector<uint8_t> m(4u << 20);
  for (size_t i = 0; i < m.size(); ++i) m[i] = uint8_t(i * 31 + (i >> 12));
  const uint64_t d = message_digest(m.data(), m.size());
  auto changed_at = [&](size_t at) {
    std::vector<uint8_t> other = m;
    other[at] ^= 0x40;
    return message_digest(other.data(), other.size()) != d;
  };
  EXPECT_TRUE(changed_at(0));
  EXPECT_TRUE(changed_at(kEndBytes - 1));
  EXPECT_TRUE(changed_at(m.size() - 1));
  EXPECT_TRUE(changed_at(m.size() - kEndBytes));
  EXPECT_TRUE(changed_at(sample_at(m.size(), 10) + 5));                  // inside a sampled block
  EXPECT_FALSE(changed_at(sample_at(m.size(), 10) + kSampleBytes + 5));  // between samples: not read
  EXPECT_TRUE(changed_at(sample_at(m.size(), kSamples - 1) + kSampleBytes - 1));
  EXPECT_LE(sample_at(m.size(), kSamples - 1) + kSampleBytes, m.size() - kEndBytes);
  std::vector<uint8_t> smallest(kWholeBytes + 1, 5);  // the smallest message sampled: its last sample read too
  const uint64_t ds = message_digest(smallest.data(), smallest.size());
  smallest[sample_at(smallest.size(), kSamples - 1) + kSampleBytes - 1] ^= 1;
  EXPECT_NE(message_digest(smallest.data(), smallest.size()), ds);
  EXPECT_NE(message_digest(m.data(), m.size() - 1), d);
}
