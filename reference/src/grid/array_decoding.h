// spec: 5.7 array() without prediction, decoding only: the detail bands, the
// no-data mask and the residual, which hold most of the coded symbols of a grid.
//
// codeArray() (coefficient_coding.h) walks the same arrays for the encoder and
// for predicted arrays; this is the same walk, bit for bit, written for the
// decoder's hot path: the range decoder's state lives in locals, the values go
// straight to their place in a strided destination (a band's box in the padded
// array), dequantised there, and the contexts come from a compact array of
// magnitudes. A test decodes random and encoded payloads both ways and compares
// values and decoder state.
#pragma once

#include <cstddef>
#include <cstdint>

#include "bitstream/range_decoder.h"
#include "grid/coefficient_coding.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv {

// Where decoded values go: value (x, y, z) of the box at
// data[x + y * row_stride + z * slice_stride], with row_stride >= size[0] and
// slice_stride >= row_stride * size[1].
struct ArrayDestination {
  int64_t* data;
  size_t row_stride, slice_stride;
  // 0: each value is its symbol (mask, residual). Otherwise a band's step: the
  // value is the symbol dequantised (spec 5.4), dequantizeSymbol().
  uint64_t step = 0;
  // When not null, the symbols themselves go to `narrow` instead, as 16-bit
  // values at the same strides (`data` and `step` are not used), and
  // *narrow_fits says whether every one of them fits (|symbol| < 2^15). When
  // one does not, what is stored for it is unspecified, and so is everything
  // decoded after it, the result included: the contexts read the stored
  // signs; the caller then decodes the array again, into int64 values. Half
  // the memory of a band, for a caller that dequantises later.
  int16_t* narrow = nullptr;
  bool* narrow_fits = nullptr;
};

// spec: 5.4 q * step, computed exactly and saturated to +-kValueLimit; step > 0.
inline int64_t dequantizeSymbol(int64_t q, uint64_t step) {
  using wavelet::kValueLimit;
  const uint64_t mag = magnitudeOf(q);
  const uint64_t limit = static_cast<uint64_t>(kValueLimit) / step;
  const int64_t v = mag > limit ? kValueLimit : static_cast<int64_t>(mag * step);
  return q < 0 ? -v : v;
}

// Decodes array() over `box` without prediction (spec 5.6, 5.7). `skip` (may
// be null) marks positions, in raster order of the box, that are not coded and
// get 0. Every position of the box is written. `magnitudes` is scratch of
// box.count() entries. Returns false when a magnitude prefix is longer than
// kMaxMagnitudeBits - 1 (spec 5.7.3 step 5); overrun and consumed bytes are
// left in `rc` as codeArray() leaves them.
bool decodeUnpredictedArray(RangeDecoder* rc, const ArrayBox& box, const uint8_t* skip,
                            const ArrayDestination& out, uint16_t* magnitudes);

}  // namespace mrsv
