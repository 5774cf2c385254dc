// Rate-distortion optimised quantisation of a detail band (informative 5.9).
// Encoder only: any integers are a valid band, so a decoder never sees this.
#pragma once

#include <cstdint>

#include "grid/coefficient_coding.h"

namespace mrsv {

// Chooses the integers `q` of a band coded as an array without prediction
// (spec 5.7) for the coefficients `scaled` (divided by the band's step, band
// order), minimising (scaled - q)^2 + lambda * bits, where bits is the cost
// of q under the adaptive models of 5.7 as the encoder will have them.
// Greedy in coding order: each position chooses among round(|c|),
// round(|c|) - 1 and 0 (magnitudes at most `q_limit`), and each block then
// chooses between its coded content and the all-zero flag. Returns whether
// any value is non-zero.
bool rdQuantizeArray(const double* scaled, const ArrayBox& box, double lambda, int64_t q_limit,
                     int64_t* q);

}  // namespace mrsv
