// Decoding of wavelet-coded grids (coding 1). spec: 5.
#pragma once

#include "mrsv/grid.h"

namespace mrsv {

// Continues decodeGrid() once the container is framed and GHDR parsed (in
// `out`): applies the chunk rules of spec 5.1 and produces the samples.
Error decodeWaveletGrid(const DecodeOptions& options, DecodedGrid* out);

}  // namespace mrsv
