// The CDF 9/7 analysis of one level computed a strip at a time along the
// grid's slowest axis, for an encoder that does not hold the grid (informative
// 5.9, out-of-core precincts). Every output value is computed from the same
// inputs by the same operations as analyze() computes it, so the
// coefficients are the same bits: the lifting steps reach 4 inputs either
// side, and a strip read 8 rows beyond the outputs it keeps (from an even
// row, so that the parities agree) makes its wrong values at the strip's own
// ends only where no kept output looks.
#pragma once

#include <cstdint>
#include <vector>

#include "wavelet/axis_plan.h"

namespace mrsv::wavelet {

// Level `level` of a grid plan whose axes all have the 9/7 order, along the
// slowest axis s = num_dims - 1. A row is the level's input box less axis s
// (box[0] values in 2-D, box[0] * box[1] in 3-D, x fastest).
struct StripLevel {
  int level = 1;
  int axis = 0;           // s
  uint32_t box[3] = {1, 1, 1};  // the level's input: size(level - 1) per axis
  bool split = false;     // axis s is transformed at this level
  uint32_t lows = 0;      // rows of the low part along s (box[s] when not split)
  uint32_t highs = 0;     // rows of the high part (0 when not split)
  uint64_t rowSize() const;
};

// Along `axis`, or by default the slowest axis num_dims - 1.
StripLevel stripLevel(const GridPlan& plan, int level, int axis = -1);

// The input rows [*first, *first + *count) that outputs [k0, k1) of the low
// and of the high part need.
void stripInput(const StripLevel& s, uint32_t k0, uint32_t k1, uint32_t* first, uint32_t* count);

// The pass of one level along s.axis over an array of `dims` (x fastest)
// whose lines along that axis are the level's [first, first + count): on
// return `data` holds, along that axis, the low lines [k0, min(k1, lows))
// then the high lines [k0, min(k1, highs)), and dims[s.axis] their count.
// The other axes are untouched (a 3-D piece lifts z, then y, then x).
void keepAlong(const StripLevel& s, uint32_t dims[3], std::vector<double>* data, uint32_t first, uint32_t count,
               uint32_t k0, uint32_t k1, int threads = 1);

// The passes of one level along every axis below `axis` that the level
// splits, in analyze()'s order (y, then x).
void analyzeBelow(const GridPlan& plan, int level, int axis, const uint32_t dims[3], double* data, int threads = 1);

}  // namespace mrsv::wavelet
