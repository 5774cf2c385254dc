// Decoding of wavelet-coded grids (coding 1). spec: 5.
#pragma once

#include <vector>

#include "mrsv/grid.h"
#include "wavelet/axis_plan.h"

namespace mrsv {

// The dequantised coefficients of a wavelet-coded grid as synthesis reads them:
// the padded array of `plan` in the Mallat layout, the bands not (yet) in the
// stream zero. For the quadtree's detail signals (spec 9.2), which synthesise
// each level twice.
struct WaveletCoefficients {
  wavelet::GridPlan plan;
  std::vector<int64_t> values;
};

// Continues decodeGrid() once the container is framed and GHDR parsed (in
// `out`): applies the chunk rules of spec 5.1 and produces the samples.
// With `coefficients`, also copies them there before synthesis; only done when
// the whole array is synthesised at once (DecodeOptions::whole_array_synthesis,
// or float samples, or reduce_levels), else left empty.
Error decodeWaveletGrid(const DecodeOptions& options, DecodedGrid* out,
                        WaveletCoefficients* coefficients = nullptr);

// decodeGrid() that also hands out the coefficients of a wavelet-coded grid
// as decodeWaveletGrid() does (grid_decode.cpp).
Error decodeGridKeepingCoefficients(const uint8_t* data, size_t size, const DecodeOptions& options,
                                    DecodedGrid* out, WaveletCoefficients* coefficients);

}  // namespace mrsv
