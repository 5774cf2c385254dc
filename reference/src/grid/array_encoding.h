// Encoder side of coded arrays (spec 5.7, 5.10) and of blocked arrays (5.7.6).
#pragma once

#include <cstdint>
#include <vector>

#include "grid/coefficient_coding.h"
#include "mrsv/encode.h"
#include "mrsv/grid.h"

namespace mrsv {

// Appends one coded array in the stream's entropy mode (spec 5.7 or 5.10).
void encodeArray(uint8_t entropy_mode, int64_t* values, const ArrayBox& box, ArrayPrediction prediction,
                 const uint8_t* skip, std::vector<uint8_t>* out);

// spec: 5.7.6 one coded array, in blocks apart when the header has precincts.
// `values` is contiguous over `box`; with `fill_valid` the voids of each coded
// array are filled with its predictions first (the coarsest block of samples).
void encodeBlockedArray(const WaveletHeader& wh, int64_t* values, const ArrayBox& box, const int resolution[3],
                        ArrayPrediction prediction, const uint8_t* skip, const uint8_t* fill_valid,
                        std::vector<uint8_t>* out);

// spec 5.5: the first 12 bytes of a GBND payload (band index, band_flags
// 0 until the prediction is known, reserved, fixed-point step).
std::vector<uint8_t> bandChunkHead(uint16_t index, uint64_t step);

// spec 5.5, 5.7.4, 5.7.5: the coarsest band's integers `q` (band order over
// `box`) coded with neighbour prediction and, with range coding, weighted
// prediction; the smaller kept (5.9), or the one `prediction` names (weighted
// exists only with range coding, 5.3: neighbour otherwise). Returns the
// band_flags prediction code; `out` gets the coded (blocked) array.
uint8_t encodeCoarsestBand(const WaveletHeader& wh, const std::vector<int64_t>& q, const ArrayBox& box,
                           const int resolution[3], WaveletEncodeOptions::Prediction prediction,
                           const uint8_t* fill_valid, std::vector<uint8_t>* out);

}  // namespace mrsv
