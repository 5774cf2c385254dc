// spec: 5.8.2 the integer samples of a run of synthesised values, for the runs
// without mask or residual (nearly all of them): the decoder's last loop over
// every sample. Internal to the grid decoder (wavelet_decode.cpp).
//
// One portable loop, compiled twice: for the baseline CPU and, on x86-64, for
// CPUs with AVX-512 F, chosen at run time. AVX-512 has the 64-bit arithmetic
// shift, minimum and maximum and the narrowing stores the loop needs, so the
// compiler vectorises it there; the arithmetic is the same integer arithmetic
// either way.
#pragma once

#include <cstddef>
#include <cstdint>

namespace mrsv {

// out gets n samples of type T (uint8_t, int16_t, uint16_t or int32_t),
// little-endian: sample i = clamp_T(offset + floor((values[i] + 2^(w-1)) /
// 2^w)) (x̂ = values[i] when w = 0). Needs |values[i]| <= 2^62 and |offset| <=
// 2^62 (the synthesised values are within +-(2^35 - 1), value_offset within
// 2^40), 0 <= w <= 24.
template <class T>
void integerSampleRun(const int64_t* values, uint8_t* out, size_t n, int w, int64_t offset);

}  // namespace mrsv
