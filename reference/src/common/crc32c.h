// CRC-32C (Castagnoli), the chunk checksum of spec 2.3.
#pragma once

#include <cstddef>
#include <cstdint>

namespace mrsv {

// Extends `crc` (0 to start) over `size` bytes. crc32c("123456789") == 0xE3069283.
// The processor's crc32 instruction where it has one (SSE4.2), else tables.
uint32_t crc32c(uint32_t crc, const uint8_t* data, size_t size);

// The table computation, for processors without the instruction (and tests).
uint32_t crc32cPortable(uint32_t crc, const uint8_t* data, size_t size);

// The CRC of A followed by B from crc32c(0, A), crc32c(0, B) and B's length:
// a chunk whose parts were checksummed apart (by the ranks that wrote them).
uint32_t crc32cCombine(uint32_t crc_a, uint32_t crc_b, uint64_t length_b);

}  // namespace mrsv
