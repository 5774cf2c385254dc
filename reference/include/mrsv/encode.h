// Encoders. Deterministic: the same grid, metadata and options give the same bytes.
#pragma once

#include <cstdint>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/metadata.h"
#include "mrsv/status.h"

namespace mrsv {

// Writes a grid with stored (uncompressed, lossless) samples: GHDR, meta (when
// not empty), GRAW, MEND. `samples` are little-endian, x fastest.
// Returns kInvalidArgument with the rule broken when the input cannot be
// represented (dimensions beyond the limits, sample count mismatch, bad metadata).
Error encodeStoredGrid(const GridHeader& header, const std::vector<uint8_t>& samples,
                       const Metadata& metadata, std::vector<uint8_t>* out);

}  // namespace mrsv
