// spec: 4.5 fixed-point synthesis, 4.6 accumulator bound.
#include "wavelet/synthesis_fixed.h"

#include <vector>

#include "wavelet/level_filters.h"
#include "wavelet/line_batches.h"

namespace mrsv::wavelet {
namespace {

int64_t saturate(int64_t v) {
  return v > kValueLimit ? kValueLimit : v < -kValueLimit ? -kValueLimit : v;
}

// floor(v / 2^kTapFracBits). C++17 leaves >> of a negative value to the
// implementation; ~(~v >> s) shifts a non-negative value and is the floor for v < 0.
int64_t shiftFloor(int64_t v) { return v >= 0 ? v >> kTapFracBits : ~(~v >> kTapFracBits); }

// spec: 4.5, one pass over a batch of `width` lines. `in` holds per line the
// coarse() scaling coefficients then the wavelets() wavelet coefficients, each
// already in [-kValueLimit, kValueLimit]; `out` receives the fine() values.
//
// Why acc cannot overflow (spec 4.6): acc[i] = sum over the P and Q columns that
// reach fine row i of tap * value. Each |tap| <= 2^24 and |value| <= 2^35 - 1, so
// each product is below 2^59; the taps of one row have sum |tap| <= kMaxRowTapSum
// = 44656268 < 2^25.42 (order 4; the generator computes it and a test rechecks
// it), so every partial sum, in whatever order the columns are visited, is at most
// 44656268 * (2^35 - 1) < 2^60.43, and adding 2^23 for the rounding keeps it below
// 2^61 < 2^63. The static_assert in synthesis_fixed.h checks the same inequality.
void synthesizeBatch(const LevelFilters& f, const int64_t* in, int64_t* out, int width) {
  const uint32_t fine = f.fine(), coarse = f.coarse(), wavelets = f.wavelets();
  const size_t w = static_cast<size_t>(width);
  for (size_t i = 0; i < fine * w; ++i) out[i] = 0;
  auto add = [&](const Column& col, const int64_t* value) {
    int64_t* acc = out + col.first_row * w;
    for (int r = 0; r < col.count; ++r, acc += w) {
      const int64_t tap = col.fixed[r];
      for (size_t l = 0; l < w; ++l) acc[l] += tap * value[l];
    }
  };
  for (uint32_t j = 0; j < coarse; ++j) add(f.p(j), in + j * w);
  for (uint32_t j = 0; j < wavelets; ++j) add(f.q(j), in + (coarse + j) * w);
  const int64_t half = int64_t{1} << (kTapFracBits - 1);
  for (size_t i = 0; i < fine * w; ++i) out[i] = saturate(shiftFloor(out[i] + half));
}

}  // namespace

// spec: 4.5
void synthesizeFixed(const GridPlan& plan, int64_t* data, int stop_level) {
  if (!isValidGridPlan(plan)) return;
  if (stop_level < 0) stop_level = 0;
  uint32_t padded[3];
  for (int a = 0; a < 3; ++a) padded[a] = plan.axis[a].size(0);
  std::vector<int64_t> in, out;
  for (int level = plan.maxLevels(); level > stop_level; --level) {
    uint32_t box[3];
    for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(level - 1);
    for (int a = 0; a < 3; ++a) {  // x, then y, then z
      const AxisPlan& axis = plan.axis[a];
      if (axis.levels < level) continue;
      const LevelFilters filters(axis.order, axis.intervals(level));
      forEachLineBatch(padded, box, a, data, &in, &out,
                       [&](int64_t* src, int64_t* dst, int width) {
                         // Inputs are saturated as they are read (a no-op for
                         // conforming input) so that the bound of 4.6 holds for any
                         // data a caller passes in.
                         for (size_t i = 0; i < size_t{box[a]} * width; ++i)
                           src[i] = saturate(src[i]);
                         synthesizeBatch(filters, src, dst, width);
                       });
    }
  }
}

}  // namespace mrsv::wavelet
