#include "common/crc32c.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mrsv {
namespace {

uint32_t crcOf(const std::string& s) {
  return crc32c(0, reinterpret_cast<const uint8_t*>(s.data()), s.size());
}

TEST(Crc32c, KnownCheckValue) { EXPECT_EQ(crcOf("123456789"), 0xE3069283u); }

TEST(Crc32c, EmptyIsZero) { EXPECT_EQ(crcOf(""), 0u); }

// RFC 3720 (iSCSI) appendix B.4 test patterns.
TEST(Crc32c, Rfc3720Patterns) {
  std::vector<uint8_t> zeros(32, 0x00), ones(32, 0xFF), inc(32), dec(32);
  for (int i = 0; i < 32; ++i) {
    inc[i] = static_cast<uint8_t>(i);
    dec[i] = static_cast<uint8_t>(31 - i);
  }
  EXPECT_EQ(crc32c(0, zeros.data(), 32), 0x8A9136AAu);
  EXPECT_EQ(crc32c(0, ones.data(), 32), 0x62A8AB43u);
  EXPECT_EQ(crc32c(0, inc.data(), 32), 0x46DD794Eu);
  EXPECT_EQ(crc32c(0, dec.data(), 32), 0x113FDB5Cu);
}

TEST(Crc32c, IncrementalEqualsOneShotAtEverySplit) {
  std::string s = "The quick brown fox jumps over the lazy dog, twice over: 0123456789";
  const auto* p = reinterpret_cast<const uint8_t*>(s.data());
  uint32_t whole = crc32c(0, p, s.size());
  for (size_t split = 0; split <= s.size(); ++split)
    EXPECT_EQ(crc32c(crc32c(0, p, split), p + split, s.size() - split), whole) << split;
}

// Parts checksummed apart combine to the whole's CRC, whatever the split
// (empty parts and parts longer than a power of two included).
TEST(Crc32c, CombinedPartsGiveTheWhole) {
  std::vector<uint8_t> data(70000);
  uint32_t x = 99;
  for (uint8_t& b : data) b = static_cast<uint8_t>((x = x * 1103515245u + 12345u) >> 24);
  const uint32_t whole = crc32c(0, data.data(), data.size());
  for (size_t split : {size_t{0}, size_t{1}, size_t{8}, size_t{4095}, size_t{65536}, data.size() - 1, data.size()}) {
    const uint32_t a = crc32c(0, data.data(), split), b = crc32c(0, data.data() + split, data.size() - split);
    EXPECT_EQ(crc32cCombine(a, b, data.size() - split), whole) << split;
  }
  // Three parts, combined left to right.
  const uint32_t ab = crc32cCombine(crc32c(0, data.data(), 100), crc32c(0, data.data() + 100, 900), 900);
  EXPECT_EQ(crc32cCombine(ab, crc32c(0, data.data() + 1000, 69000), 69000), whole);
}

// The instruction path and the tables agree on every length and alignment.
TEST(Crc32c, HardwareAndTablesAgree) {
  std::vector<uint8_t> data(4099);
  uint32_t x = 12345;
  for (uint8_t& b : data) b = static_cast<uint8_t>((x = x * 1103515245u + 12345u) >> 24);
  for (size_t start : {0u, 1u, 3u, 7u})
    for (size_t size : {0u, 1u, 7u, 8u, 9u, 63u, 64u, 1000u, 4090u})
      EXPECT_EQ(crc32c(0x1234u, data.data() + start, size), crc32cPortable(0x1234u, data.data() + start, size))
          << start << " " << size;
}

}  // namespace
}  // namespace mrsv
