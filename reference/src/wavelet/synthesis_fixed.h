// The normative decoder transform: fixed-point B-spline wavelet synthesis.
// spec: 4.5 (algorithm), 4.6 (no overflow), 4.7 (agreement with the real transform).
//
// Decode side: integers only, no Eigen.
#pragma once

#include <climits>
#include <cstdint>

#include "wavelet/axis_plan.h"
#include "wavelet/filter_tables.h"  // kTapFracBits = 24

namespace mrsv::wavelet {

// Saturation bound of every stored value. spec: 4.5
constexpr int64_t kValueLimit = (int64_t{1} << 35) - 1;

// sat of spec 4.5 and 4.11.3: clamps to [-kValueLimit, kValueLimit].
inline int64_t saturate(int64_t v) { return v > kValueLimit ? kValueLimit : v < -kValueLimit ? -kValueLimit : v; }

// floor(v / 2^24), the flooring shift of spec 4.1 by kTapFracBits (24, also the
// 9/7 lifting's fraction bits). C++17 leaves >> of a negative value to the
// implementation; ~(~v >> s) shifts a non-negative value and is the floor for v < 0.
inline int64_t shiftFloor(int64_t v) { return v >= 0 ? v >> kTapFracBits : ~(~v >> kTapFracBits); }

// spec: 4.5. `data` holds the padded array (plan.paddedCount() values, x fastest,
// then y, then z) in the Mallat layout, values in fixed point (any scale the codec
// chooses), each already saturated to [-kValueLimit, kValueLimit] (values outside are
// saturated when read, so any int64 input is safe). Runs the inverse transform from
// the coarsest level down to level `stop_level` (0 = full resolution); after it the
// low-pass block of level stop_level (sizes axis[i].size(min(stop_level, levels_i)))
// sits at the front of each axis, with the strides of the padded array.
//
// At each level j = maxLevels, ..., stop_level + 1 the axes that are split at j are
// synthesized x first, then y, then z, each over every line of the box of sizes
// axis[b].size(j - 1). Each 1-D output value is
//   sat((sum of tap*value over the P and Q taps + 2^(kTapFracBits-1)) >> kTapFracBits)
// with an arithmetic (flooring) shift, where sat clamps to [-kValueLimit, kValueLimit].
// The int64 accumulator cannot overflow: see kAccumulatorBound below and spec 4.6.
// Does nothing when !isValidGridPlan(plan); `data` must hold plan.paddedCount() values.
//
// With start_level below maxLevels, the levels above it are taken as already
// synthesised (a call that stopped at start_level): the synthesis resumes
// there, so that a decoder can go down one level at a time as bands arrive
// and end with the same values as one call.
void synthesizeFixed(const GridPlan& plan, int64_t* data, int stop_level = 0,
                     int start_level = INT_MAX);

// spec: 4.6. The largest |accumulator| any row can reach: every partial sum of a
// row is bounded by the sum of |tap| * |value| over the row, and the table generator
// gives sum |tap| <= kMaxRowTapSum (44656268 < 2^25.42) for every row of every order.
constexpr int64_t kAccumulatorBound =
    kMaxRowTapSum * kValueLimit + (int64_t{1} << (kTapFracBits - 1));
static_assert(kMaxRowTapSum <= (INT64_MAX - (int64_t{1} << (kTapFracBits - 1))) / kValueLimit,
              "the fixed-point accumulator could overflow");

}  // namespace mrsv::wavelet
