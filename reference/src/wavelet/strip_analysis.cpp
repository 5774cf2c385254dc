// Informative 5.9: one level of the 9/7 analysis, a strip at a time.
#include "wavelet/strip_analysis.h"

#include <algorithm>

#include "common/parallel_for.h"
#include "wavelet/cdf97.h"
#include "wavelet/line_batches.h"

namespace mrsv::wavelet {
namespace {

// Reach of the four lifting steps (4), doubled: an even number of rows.
constexpr uint32_t kStripMargin = 8;

// analyze()'s pass along one axis, over an array of `dims` (x fastest), its
// lines shared among `threads` threads (each line is computed alike
// whichever thread has it, so the values are the same bits).
void analyzeAxis(const uint32_t dims[3], int axis, double* data, int threads) {
  // The lines are cut along another axis: x for y and z passes, else the slowest.
  const int cut = axis != 0 ? 0 : dims[2] > 1 ? 2 : 1;
  const uint64_t stride[3] = {1, dims[0], uint64_t{dims[0]} * dims[1]};
  const uint32_t parts = static_cast<uint32_t>(std::clamp<int64_t>(threads, 1, std::max<uint32_t>(dims[cut] / 16, 1)));
  parallelFor(parts, static_cast<int>(parts), [&](uint64_t part) {
    const uint32_t lo = static_cast<uint32_t>(dims[cut] * part / parts);
    const uint32_t hi = static_cast<uint32_t>(dims[cut] * (part + 1) / parts);
    uint32_t box[3] = {dims[0], dims[1], dims[2]};
    box[cut] = hi - lo;
    std::vector<double> in, out;
    forEachLineBatch(dims, box, axis, data + lo * stride[cut], &in, &out, [&](double* src, double* dst, int width) {
      analyzeCdf97Lines(src, dst, box[axis], width);
    });
  });
}

}  // namespace

uint64_t StripLevel::rowSize() const {
  uint64_t n = 1;
  for (int a = 0; a < axis; ++a) n *= box[a];
  return n;
}

StripLevel stripLevel(const GridPlan& plan, int level, int axis) {
  StripLevel s;
  s.level = level;
  s.axis = axis < 0 ? plan.num_dims - 1 : axis;
  for (int a = 0; a < 3; ++a) s.box[a] = plan.axis[a].size(level - 1);
  s.split = plan.axis[s.axis].levels >= level;
  s.lows = s.split ? plan.axis[s.axis].size(level) : s.box[s.axis];
  s.highs = s.box[s.axis] - s.lows;
  return s;
}

void stripInput(const StripLevel& s, uint32_t k0, uint32_t k1, uint32_t* first, uint32_t* count) {
  const uint32_t n = s.box[s.axis];
  if (!s.split) {
    *first = std::min(k0, n);
    *count = std::min(k1, n) - *first;
    return;
  }
  const uint64_t lo = 2 * uint64_t{k0}, hi = 2 * uint64_t{k1};
  *first = static_cast<uint32_t>(lo > kStripMargin ? lo - kStripMargin : 0);
  *count = static_cast<uint32_t>(std::min<uint64_t>(n, hi + kStripMargin) - *first);
}

void keepAlong(const StripLevel& s, uint32_t dims[3], std::vector<double>* data, uint32_t first, uint32_t count,
               uint32_t k0, uint32_t k1, int threads) {
  dims[s.axis] = count;
  if (!s.split) return;
  double* d = data->data();
  analyzeAxis(dims, s.axis, d, threads);
  // Local Mallat layout along the axis: lows (count + 1) / 2 lines, then
  // highs; local line i of either part is the part's line first / 2 + i
  // (first is even). The kept lines move down in place, plane by plane in
  // increasing order: each comes from at or after its destination.
  uint64_t line = 1, planes = 1;
  for (int a = 0; a < s.axis; ++a) line *= dims[a];
  for (int a = s.axis + 1; a < 3; ++a) planes *= dims[a];
  const uint32_t local_lows = (count + 1) / 2, base = first / 2;
  const uint32_t low_end = std::min(k1, s.lows), high_end = std::min(k1, s.highs);
  std::vector<uint32_t> from;
  for (uint32_t k = k0; k < low_end; ++k) from.push_back(k - base);
  for (uint32_t k = k0; k < high_end; ++k) from.push_back(local_lows + k - base);
  const uint64_t kept = from.size();
  for (uint64_t p = 0; p < planes; ++p)
    for (uint64_t i = 0; i < kept; ++i) {
      const double* src = d + (p * count + from[i]) * line;
      double* dst = d + (p * kept + i) * line;
      if (src != dst) std::copy(src, src + line, dst);
    }
  dims[s.axis] = static_cast<uint32_t>(kept);
  data->resize(kept * line * planes);
}

void analyzeBelow(const GridPlan& plan, int level, int axis, const uint32_t dims[3], double* data, int threads) {
  for (int a = axis - 1; a >= 0; --a)
    if (plan.axis[a].levels >= level) analyzeAxis(dims, a, data, threads);
}

}  // namespace mrsv::wavelet
