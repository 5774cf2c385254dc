// spec: 4.11 (informative part) real-valued CDF 9/7 analysis and synthesis,
// the exact inverse pair that the fixed-point synthesis of 4.11.3 rounds.
#include <cstddef>
#include <vector>

#include "wavelet/cdf97.h"
#include "wavelet/line_batches.h"

namespace mrsv::wavelet {
namespace {

constexpr double kAlpha = -1.586134342059924, kBeta = -0.052980118572961,
                 kGamma = 0.882911075530934, kDelta = 0.443506852043971, kK = 1.230174104914001;

// x[p] += c * (x[p-1] + x[p+1]) for every p of `parity`, mirrored at the ends.
void lift(double* x, size_t len, int width, size_t parity, double c) {
  const size_t w = static_cast<size_t>(width);
  for (size_t p = parity; p < len; p += 2) {
    const double* left = x + (p > 0 ? p - 1 : p + 1) * w;
    const double* right = x + (p + 1 < len ? p + 1 : p - 1) * w;
    double* out = x + p * w;
    for (size_t k = 0; k < w; ++k) out[k] += c * (left[k] + right[k]);
  }
}

// Natural order in `x` (overwritten) -> low half, then high half, in `out`.
void analyzeBatch(double* x, double* out, size_t len, int width) {
  const size_t w = static_cast<size_t>(width), h = (len + 1) / 2;
  lift(x, len, width, 1, kAlpha);
  lift(x, len, width, 0, kBeta);
  lift(x, len, width, 1, kGamma);
  lift(x, len, width, 0, kDelta);
  for (size_t i = 0; i < h; ++i)
    for (size_t k = 0; k < w; ++k) out[i * w + k] = x[2 * i * w + k] / kK;
  for (size_t i = 0; i + h < len; ++i)
    for (size_t k = 0; k < w; ++k) out[(h + i) * w + k] = x[(2 * i + 1) * w + k];
}

void synthesizeBatch(const double* in, double* x, size_t len, int width) {
  const size_t w = static_cast<size_t>(width), h = (len + 1) / 2;
  for (size_t i = 0; i < h; ++i)
    for (size_t k = 0; k < w; ++k) x[2 * i * w + k] = in[i * w + k] * kK;
  for (size_t i = 0; i + h < len; ++i)
    for (size_t k = 0; k < w; ++k) x[(2 * i + 1) * w + k] = in[(h + i) * w + k];
  lift(x, len, width, 0, -kDelta);
  lift(x, len, width, 1, -kGamma);
  lift(x, len, width, 0, -kBeta);
  lift(x, len, width, 1, -kAlpha);
}

void paddedSizes(const GridPlan& plan, uint32_t padded[3]) {
  for (int a = 0; a < 3; ++a) padded[a] = plan.axis[a].size(0);
}

}  // namespace

void analyzeCdf97(const GridPlan& plan, double* data) {
  if (!isValidGridPlan(plan)) return;
  uint32_t padded[3];
  paddedSizes(plan, padded);
  std::vector<double> in, out;
  for (int level = 1; level <= plan.maxLevels(); ++level) {
    uint32_t box[3];
    for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(level - 1);
    for (int a = 2; a >= 0; --a) {  // the reverse of the synthesis order
      if (plan.axis[a].levels < level) continue;
      forEachLineBatch(padded, box, a, data, &in, &out, [&](double* src, double* dst, int width) {
        analyzeBatch(src, dst, box[a], width);
      });
    }
  }
}

void synthesizeCdf97(const GridPlan& plan, double* data, int stop_level) {
  if (!isValidGridPlan(plan)) return;
  if (stop_level < 0) stop_level = 0;
  uint32_t padded[3];
  paddedSizes(plan, padded);
  std::vector<double> in, out;
  for (int level = plan.maxLevels(); level > stop_level; --level) {
    uint32_t box[3];
    for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(level - 1);
    for (int a = 0; a < 3; ++a) {
      if (plan.axis[a].levels < level) continue;
      forEachLineBatch(padded, box, a, data, &in, &out, [&](double* src, double* dst, int width) {
        synthesizeBatch(src, dst, box[a], width);
      });
    }
  }
}

}  // namespace mrsv::wavelet
