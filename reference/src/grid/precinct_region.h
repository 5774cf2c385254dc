// Region decoding of a wavelet-coded grid in precincts (spec 5.7.6): the file
// header, the chunk headers, the GBND, GMSK and GRES headers with their tables
// of block lengths, and the blocks whose coefficients reach the region through
// the synthesis; nothing else. The samples equal the same box of a whole decode.
#pragma once

#include <cstdint>

#include "mrsv/tiled_grid.h"

namespace mrsv {

// The region of the grid `parsed` (the file up to the end of its WHDR, which
// has precincts, decoded as a prefix; the next chunk at `next`), at full
// resolution or options.reduce_levels above it (the lattice of spec 11.6, as
// a whole decode cropped gives it); options.void_values is read. Returns false, with *out untouched, when the
// stream holds anything a region decoder does not read its way (a chunk out
// of order, a table that does not add up, a block that does not decode): the
// caller then decodes the whole file, which reports the first broken rule as
// a whole decode does. CRCs of the chunks read in part are not checked (5.7.6).
bool decodePrecinctRegion(ByteSource& source, uint64_t next, const DecodedGrid& parsed,
                          const GridRegion& region, const DecodeOptions& options, DecodedGrid* out,
                          Error* io_error);

}  // namespace mrsv
