// spec 9.2: the detail signal of each level, for the quadtree's wavelet
// criterion: level m's low-pass block synthesised to level m-1 with and
// without level m's detail bands, subtracted. The decoder's own fixed-point
// synthesis (spec 4.5, 4.11.3) makes both, so the signal is exact and the same
// in every conforming implementation.
#pragma once

#include <string>

#include "grid/wavelet_decode.h"
#include "mrsv/quadtree_mesh.h"

namespace mrsv {

// The detail signals of a 2-D grid of sizes size_x x size_y from its
// coefficients; levels 1..min(levels of x, levels of y).
bool detailSignals(const WaveletCoefficients& coefficients, int frac_bits, uint32_t size_x,
                   uint32_t size_y, QuadtreeDetails* out, std::string* error);

}  // namespace mrsv
