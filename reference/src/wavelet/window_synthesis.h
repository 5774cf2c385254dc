// One step of the fixed-point synthesis (spec 4.5 for the B-spline wavelets,
// 4.11.3 for CDF 9/7) along one axis, computed for a window of its outputs
// only: what a region decoder needs (spec 5.7.6), level by level, without the
// lines' other values. Every output equals the one the whole line gives: the
// same sums of the same terms (B-splines), the same lifting steps on the values
// they read (9/7), with the mirrored ends only where the line really ends.
//
// Decode side: integers only.
#pragma once

#include <cstdint>
#include <vector>

#include "wavelet/axis_plan.h"

namespace mrsv::wavelet {

// The inputs a window of outputs reads: low-pass inputs [low0, low1) of the
// line's low part, high-pass inputs [high0, high1) of its high part (indices
// within each part; empty ranges when none).
struct WindowInputs {
  uint32_t low0 = 0, low1 = 0, high0 = 0, high1 = 0;
};

class WindowLine {
 public:
  // Level j >= 1 of an axis split there (axis.levels >= j).
  WindowLine(const AxisPlan& axis, int level);

  uint32_t fine() const { return fine_; }  // F = size(j - 1): the outputs of a line
  uint32_t low() const { return low_; }    // inputs in the low part: size(j)

  WindowInputs inputs(uint32_t out0, uint32_t out1) const;

  // Outputs out0 .. out1 - 1 to out[0 .. out1 - out0) from the inputs `in` =
  // inputs(out0, out1) names (computed once for all the lines of a pass):
  // low-pass input i (in.low0 <= i < in.low1) at low[i - in.low0], high-pass
  // input i at high[i - in.high0]. `scratch` is reused.
  void synthesize(const WindowInputs& in, const int64_t* low, const int64_t* high, uint32_t out0, uint32_t out1,
                  int64_t* out, std::vector<int64_t>* scratch) const;

 private:
  int order_;
  uint32_t fine_, low_, intervals_;
};

}  // namespace mrsv::wavelet
