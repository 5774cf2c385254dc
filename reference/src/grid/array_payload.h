// One coded array of a wavelet-coded grid, decoded from its bytes (spec 5.6,
// 5.7, or 5.10 in the baseline mode), and one sample from its synthesised
// value (5.8.2): the pieces a region decoder (grid/precinct_region.h) shares
// with the whole-grid decoder (grid/wavelet_decode.cpp).
#pragma once

#include <cstddef>
#include <cstdint>

#include "grid/array_decoding.h"
#include "mrsv/grid.h"

namespace mrsv {

// Range-coded arrays without prediction go straight to `out`, which may be
// strided and dequantise (out.step), with `magnitudes` as scratch of
// box.count() entries. The others need a contiguous `out` with step 0
// (row_stride = X, slice_stride = X * Y) and, with prediction, `symbols`:
// scratch of box.count() entries (neighbour prediction) or 2 * X (weighted).
// Errors are 206 at payload_offset, naming `field`.
Error decodeArrayPayload(uint8_t entropy_mode, const uint8_t* payload, size_t size,
                         uint64_t payload_offset, const char* field, const ArrayBox& box,
                         ArrayPrediction prediction, const uint8_t* skip,
                         const ArrayDestination& out, int64_t* symbols, uint16_t* magnitudes);

// spec: 5.8.2 an integer sample value clamped to the range of its type.
int64_t clampToType(int64_t v, SampleType type);

// spec: 5.8.2 at full resolution: the sample of synthesised value t, written to
// `out` (little-endian, sampleSize(g.sample_type) bytes): the no-data value
// when `masked`; for integer samples the residual r (times residual_step)
// added when residual_step > 0.
void sampleOfValue(const GridHeader& g, const WaveletHeader& w, int64_t t, bool masked, int64_t r,
                   uint32_t residual_step, uint8_t* out);

}  // namespace mrsv
