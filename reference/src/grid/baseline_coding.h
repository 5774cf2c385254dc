// The baseline entropy mode (entropy_mode 0, spec 5.10): the paper's JPEG-like
// coding of integer arrays, run/size symbols with a canonical Huffman table in
// the stream, then amplitude bits. Simpler and faster to implement than the
// adaptive mode, at some cost in size.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "grid/coefficient_coding.h"

namespace mrsv {

// spec: 5.10.1 symbols: run of zeros (0..15) in the high bits, size (bit length
// of the value, 0..40) in the low six. (0, 0) ends the array; (15, 0) is 16 zeros.
constexpr uint16_t kBaselineEndOfArray = 0;
constexpr uint16_t kBaselineZeroRun = 15 << 6;
constexpr int kBaselineMaxSize = 40;
constexpr int kBaselineMaxCodeLength = 20;

inline uint16_t baselineSymbol(int run, int size) { return static_cast<uint16_t>(run << 6 | size); }

// Decodes one baseline array payload (spec 5.10) into `values` over `box`, with
// optional neighbour prediction and skipped positions as in 5.7. Returns an
// empty string on success, otherwise the rule broken.
std::string decodeBaselineArray(const uint8_t* payload, size_t size, const ArrayBox& box,
                                ArrayPrediction prediction, const uint8_t* skip, int64_t* values);

// The encoder side: appends the payload for `values` to `out`. Values at skipped
// positions must be 0.
void encodeBaselineArray(const int64_t* values, const ArrayBox& box, ArrayPrediction prediction,
                         const uint8_t* skip, std::vector<uint8_t>* out);

}  // namespace mrsv
