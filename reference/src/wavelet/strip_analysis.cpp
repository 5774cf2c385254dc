// Informative 5.9: one level of the 9/7 analysis, a strip at a time.
#include "wavelet/strip_analysis.h"

#include <algorithm>

#include "wavelet/cdf97.h"
#include "wavelet/line_batches.h"

namespace mrsv::wavelet {
namespace {

// Reach of the four lifting steps (4), doubled: an even number of rows.
constexpr uint32_t kStripMargin = 8;

// analyze()'s pass along one axis, over an array of `dims` (x fastest).
void analyzeAxis(uint32_t dims[3], int axis, double* data, std::vector<double>* in, std::vector<double>* out) {
  forEachLineBatch(dims, dims, axis, data, in, out, [&](double* src, double* dst, int width) {
    analyzeCdf97Lines(src, dst, dims[axis], width);
  });
}

}  // namespace

uint64_t StripLevel::rowSize() const {
  uint64_t n = 1;
  for (int a = 0; a < axis; ++a) n *= box[a];
  return n;
}

StripLevel stripLevel(const GridPlan& plan, int level) {
  StripLevel s;
  s.level = level;
  s.axis = plan.num_dims - 1;
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

void analyzeStrip(const GridPlan& plan, const StripLevel& s, double* in, uint32_t first, uint32_t count,
                  uint32_t k0, uint32_t k1, std::vector<double>* out) {
  const uint64_t row = s.rowSize();
  std::vector<double> scratch_in, scratch_out;
  uint32_t dims[3] = {s.box[0], s.box[1], s.box[2]};
  uint32_t kept = 0;
  out->clear();
  if (s.split) {
    dims[s.axis] = count;
    analyzeAxis(dims, s.axis, in, &scratch_in, &scratch_out);
    // Strip-local Mallat layout: lows (count + 1) / 2 rows, then highs; local
    // row i of either part is the part's row first / 2 + i (first is even).
    const uint32_t local_lows = (count + 1) / 2, base = first / 2;
    const uint32_t low_end = std::min(k1, s.lows), high_end = std::min(k1, s.highs);
    for (uint32_t k = k0; k < low_end; ++k, ++kept)
      out->insert(out->end(), in + (k - base) * row, in + (k - base + 1) * row);
    for (uint32_t k = k0; k < high_end; ++k, ++kept)
      out->insert(out->end(), in + (local_lows + k - base) * row, in + (local_lows + k - base + 1) * row);
  } else {
    kept = count;
    out->assign(in, in + uint64_t{count} * row);
  }
  dims[s.axis] = kept;
  for (int a = s.axis - 1; a >= 0; --a)
    if (plan.axis[a].levels >= s.level) analyzeAxis(dims, a, out->data(), &scratch_in, &scratch_out);
}

}  // namespace mrsv::wavelet
