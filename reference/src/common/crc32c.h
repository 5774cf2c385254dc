// CRC-32C (Castagnoli), the chunk checksum of spec 2.3.
#pragma once

#include <cstddef>
#include <cstdint>

namespace mrsv {

// Extends `crc` (0 to start) over `size` bytes. crc32c("123456789") == 0xE3069283.
uint32_t crc32c(uint32_t crc, const uint8_t* data, size_t size);

}  // namespace mrsv
