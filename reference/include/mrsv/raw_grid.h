// Headerless raw sample files (the layout of ../shared/data): x fastest.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"

namespace mrsv {

enum class Endian { kLittle, kBig };

// Reverses the byte order of every sample in place (for 1-byte samples a no-op).
void swapSampleBytes(std::vector<uint8_t>* samples, size_t sample_size);

// Parses "X", "X,Y" or "X,Y,Z" into header sizes and num_dims. Returns an
// empty string on success, otherwise what is wrong.
std::string parseDims(const std::string& text, GridHeader* header);

}  // namespace mrsv
