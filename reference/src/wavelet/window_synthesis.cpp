// spec: 4.5 and 4.11.3 over a window of a line's outputs.
#include "wavelet/window_synthesis.h"

#include <algorithm>

#include "wavelet/cdf97.h"
#include "wavelet/level_filters.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv::wavelet {
namespace {

constexpr int64_t kHalf = int64_t{1} << 23;

int64_t ceilDiv2(int64_t v) { return v >= 0 ? (v + 1) / 2 : -((-v) / 2); }
int64_t floorDiv2(int64_t v) { return v >= 0 ? v / 2 : -((1 - v) / 2); }

// The columns of one matrix (P or Q) of a B-spline level that reach rows
// [r0, r1): calls visit(column, first_row, count, fixed_taps) for each.
template <class Column, class Visit>
void columnsReaching(uint32_t columns, uint32_t boundary, int interior_first, int interior_count,
                     Column column, uint32_t r0, uint32_t r1, Visit visit) {
  auto consider = [&](uint32_t j) {
    const auto c = column(j);
    if (c.first_row < r1 && c.first_row + static_cast<uint32_t>(c.count) > r0) visit(j, c);
  };
  const uint32_t nb = std::min(boundary, columns);
  for (uint32_t j = 0; j < nb; ++j) consider(j);
  // Interior column j covers rows 2j + first .. 2j + first + count - 1.
  const int64_t lo = std::max<int64_t>(nb, ceilDiv2(int64_t{r0} - interior_first - interior_count + 1));
  const int64_t hi = std::min<int64_t>(int64_t{columns} - nb - 1, floorDiv2(int64_t{r1} - 1 - interior_first));
  for (int64_t j = lo; j <= hi; ++j) consider(static_cast<uint32_t>(j));
  for (uint32_t j = std::max(nb, columns - nb); j < columns; ++j) consider(j);
}

}  // namespace

WindowLine::WindowLine(const AxisPlan& axis, int level)
    : order_(axis.order), fine_(axis.size(level - 1)), low_(axis.size(level)),
      intervals_(axis.intervals(level)) {}

WindowInputs WindowLine::inputs(uint32_t out0, uint32_t out1) const {
  WindowInputs in;
  if (out0 >= out1) return in;
  if (isCdf97(order_)) {
    // Four lifting steps, each reading one neighbour on either side.
    const int64_t p0 = std::max<int64_t>(0, int64_t{out0} - 4), p1 = std::min<int64_t>(fine_, int64_t{out1} + 4);
    in.low0 = static_cast<uint32_t>(ceilDiv2(p0));
    in.low1 = static_cast<uint32_t>(std::min<int64_t>(low_, ceilDiv2(p1)));
    in.high0 = static_cast<uint32_t>(std::max<int64_t>(0, ceilDiv2(p0 - 1)));
    in.high1 = static_cast<uint32_t>(std::min<int64_t>(fine_ - low_, ceilDiv2(p1 - 1)));
    return in;
  }
  const LevelFilters f(order_, intervals_);
  const OrderFilters& of = f.filters();
  uint32_t lo = UINT32_MAX, hi = 0;
  auto note = [&](uint32_t j, const Column&) {
    lo = std::min(lo, j);
    hi = std::max(hi, j + 1);
  };
  columnsReaching(f.coarse(), static_cast<uint32_t>(of.p_boundary), of.p_interior_first, of.p_interior_count,
                  [&](uint32_t j) { return f.p(j); }, out0, out1, note);
  if (lo < hi) in.low0 = lo, in.low1 = hi;
  lo = UINT32_MAX, hi = 0;
  columnsReaching(f.wavelets(), static_cast<uint32_t>(of.q_boundary), of.q_interior_first, of.q_interior_count,
                  [&](uint32_t j) { return f.q(j); }, out0, out1, note);
  if (lo < hi) in.high0 = lo, in.high1 = hi;
  return in;
}

void WindowLine::synthesize(const WindowInputs& in, const int64_t* low, const int64_t* high, uint32_t out0,
                            uint32_t out1, int64_t* out, std::vector<int64_t>* scratch) const {
  if (out0 >= out1) return;
  if (isCdf97(order_)) {
    // spec 4.11.3 on positions [p0, p1): the scaled low values at even
    // positions, the high values at odd ones, then step t = 1..4 on the
    // positions of its parity in [out0 - 4 + t, out1 + 4 - t), whose
    // neighbours the step before has made (or the line's mirrored ends).
    const int64_t F = fine_;
    const int64_t p0 = std::max<int64_t>(0, int64_t{out0} - 4), p1 = std::min<int64_t>(F, int64_t{out1} + 4);
    scratch->resize(static_cast<size_t>(p1 - p0));
    int64_t* x = scratch->data() - p0;  // x[i] for p0 <= i < p1
    for (int64_t i = p0; i < p1; ++i)
      x[i] = i % 2 == 0 ? saturate(shiftFloor(saturate(low[i / 2 - in.low0]) * kCdf97K + kHalf))
                        : saturate(high[i / 2 - in.high0]);
    static const struct {
      int parity;
      int64_t c;
    } kSteps[4] = {{0, kCdf97Delta}, {1, kCdf97Gamma}, {0, kCdf97Beta}, {1, kCdf97Alpha}};
    for (int t = 1; t <= 4; ++t) {
      const int64_t a = std::max<int64_t>(0, int64_t{out0} - 4 + t), b = std::min<int64_t>(F, int64_t{out1} + 4 - t);
      const int p = kSteps[t - 1].parity;
      const int64_t c = kSteps[t - 1].c;
      for (int64_t i = a + ((a & 1) != p); i < b; i += 2) {
        const int64_t l = i > 0 ? i - 1 : i + 1, r = i + 1 < F ? i + 1 : i - 1;
        x[i] = saturate(x[i] - shiftFloor(c * (x[l] + x[r]) + kHalf));
      }
    }
    std::copy(x + out0, x + out1, out);
    return;
  }
  // spec 4.5: out[i] = sat((sum of P taps * low inputs + Q taps * high inputs
  // of row i + 2^23) >> 24), the sums gathered column by column.
  const LevelFilters f(order_, intervals_);
  const OrderFilters& of = f.filters();
  scratch->assign(out1 - out0, kHalf);
  int64_t* acc = scratch->data();
  auto add = [&](const int64_t* inputs, uint32_t first) {
    return [&, inputs, first](uint32_t j, const Column& c) {
      const int64_t v = saturate(inputs[j - first]);
      for (int r = 0; r < c.count; ++r) {
        const uint32_t row = c.first_row + static_cast<uint32_t>(r);
        if (row >= out0 && row < out1) acc[row - out0] += int64_t{c.fixed[r]} * v;
      }
    };
  };
  columnsReaching(f.coarse(), static_cast<uint32_t>(of.p_boundary), of.p_interior_first, of.p_interior_count,
                  [&](uint32_t j) { return f.p(j); }, out0, out1, add(low, in.low0));
  columnsReaching(f.wavelets(), static_cast<uint32_t>(of.q_boundary), of.q_interior_first, of.q_interior_count,
                  [&](uint32_t j) { return f.q(j); }, out0, out1, add(high, in.high0));
  for (uint32_t i = 0; i < out1 - out0; ++i) out[i] = saturate(shiftFloor(acc[i]));
}

}  // namespace mrsv::wavelet
