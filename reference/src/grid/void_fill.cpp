// Encoder-side filling of no-data samples (informative 5.9 item 3).
#include "grid/void_fill.h"

#include <algorithm>
#include <cmath>

#include "wavelet/transform_float.h"

namespace mrsv {

void fillVoidsPullPush(std::vector<double>* x, const std::vector<uint8_t>& valid, const uint32_t size[3]) {
  struct Level {
    uint32_t size[3];
    std::vector<double> sum;
    std::vector<double> weight;
  };
  std::vector<Level> pyramid(1);
  Level& base = pyramid[0];
  std::copy(size, size + 3, base.size);
  base.sum.resize(x->size());
  base.weight.resize(x->size());
  for (size_t i = 0; i < x->size(); ++i) {
    base.weight[i] = valid[i] ? 1.0 : 0.0;
    base.sum[i] = valid[i] ? (*x)[i] : 0.0;
  }
  while (pyramid.back().size[0] > 1 || pyramid.back().size[1] > 1 || pyramid.back().size[2] > 1) {
    const Level& fine = pyramid.back();
    Level coarse;
    for (int a = 0; a < 3; ++a) coarse.size[a] = (fine.size[a] + 1) / 2;
    size_t n = size_t{coarse.size[0]} * coarse.size[1] * coarse.size[2];
    coarse.sum.assign(n, 0.0);
    coarse.weight.assign(n, 0.0);
    for (uint32_t z = 0; z < fine.size[2]; ++z)
      for (uint32_t y = 0; y < fine.size[1]; ++y)
        for (uint32_t xx = 0; xx < fine.size[0]; ++xx) {
          size_t f = xx + fine.size[0] * (y + size_t{fine.size[1]} * z);
          size_t c = xx / 2 + coarse.size[0] * (y / 2 + size_t{coarse.size[1]} * (z / 2));
          coarse.sum[c] += fine.sum[f];
          coarse.weight[c] += fine.weight[f];
        }
    pyramid.push_back(std::move(coarse));
  }
  // Push: a cell without valid samples takes its parent's average.
  for (size_t l = pyramid.size() - 1; l-- > 0;) {
    Level& fine = pyramid[l];
    const Level& coarse = pyramid[l + 1];
    for (uint32_t z = 0; z < fine.size[2]; ++z)
      for (uint32_t y = 0; y < fine.size[1]; ++y)
        for (uint32_t xx = 0; xx < fine.size[0]; ++xx) {
          size_t f = xx + fine.size[0] * (y + size_t{fine.size[1]} * z);
          size_t c = xx / 2 + coarse.size[0] * (y / 2 + size_t{coarse.size[1]} * (z / 2));
          if (fine.weight[f] == 0 && coarse.weight[c] > 0) {
            fine.sum[f] = coarse.sum[c] / coarse.weight[c];
            fine.weight[f] = 1;
          } else if (fine.weight[f] > 0) {
            fine.sum[f] /= fine.weight[f];
            fine.weight[f] = 1;
          }
        }
  }
  const Level& filled = pyramid[0];  // `base` dangles once the pyramid has grown
  for (size_t i = 0; i < x->size(); ++i)
    if (!valid[i]) (*x)[i] = filled.weight[i] > 0 ? filled.sum[i] : 0.0;
}

void analyzeSamples(const wavelet::GridPlan& plan, const uint32_t size[3], const std::vector<double>& x,
                    std::vector<double>* coefficients) {
  const uint32_t px = plan.axis[0].size(0), py = plan.axis[1].size(0), pz = plan.axis[2].size(0);
  coefficients->assign(plan.paddedCount(), 0.0);
  for (uint32_t z = 0; z < pz; ++z)
    for (uint32_t y = 0; y < py; ++y)
      for (uint32_t xx = 0; xx < px; ++xx) {
        const uint32_t sx = std::min(xx, size[0] - 1), sy = std::min(y, size[1] - 1),
                       sz = std::min(z, size[2] - 1);
        (*coefficients)[xx + px * (y + size_t{py} * z)] = x[sx + size[0] * (sy + size_t{size[1]} * sz)];
      }
  wavelet::analyze(plan, coefficients->data());
}

void refineVoidFill(const wavelet::GridPlan& plan, const uint32_t size[3],
                    const std::vector<wavelet::Band>& bands, const std::vector<double>& band_gain,
                    const std::vector<uint8_t>& valid, double range, std::vector<double>* x,
                    std::vector<double>* coefficients) {
  // Measured on the Everest and Rainier tiles (decision D27): thresholds from
  // range / 8 down to range / 200 in 16 steps. Halving both, or 24 steps from
  // range / 4, changed the PSNR by under 0.05 dB; one fixed threshold gained
  // much less.
  constexpr int kIterations = 16;
  const double first = range / 8, last = range / 200;
  // Without detail bands (the predictive route) there is nothing to threshold.
  if (!(range > 0) || plan.maxLevels() == 0) return;
  const uint64_t px = plan.axis[0].size(0), pxy = px * plan.axis[1].size(0);
  std::vector<double> sparse;
  for (int it = 0; it < kIterations; ++it) {
    const double threshold = first * std::pow(last / first, it / double(kIterations - 1));
    sparse = *coefficients;
    for (size_t b = 0; b < bands.size(); ++b) {
      const wavelet::Band& band = bands[b];
      if (band.mask == 0) continue;  // the coarsest block is kept whole
      const double limit = threshold / band_gain[b];
      for (uint32_t z = 0; z < band.size[2]; ++z)
        for (uint32_t y = 0; y < band.size[1]; ++y) {
          double* row = sparse.data() + band.offset[0] + (band.offset[1] + y) * px + (band.offset[2] + z) * pxy;
          for (uint32_t i = 0; i < band.size[0]; ++i)
            if (std::fabs(row[i]) < limit) row[i] = 0;
        }
    }
    wavelet::synthesize(plan, sparse.data());
    for (uint32_t z = 0; z < size[2]; ++z)
      for (uint32_t y = 0; y < size[1]; ++y)
        for (uint32_t i = 0; i < size[0]; ++i) {
          const size_t at = i + size[0] * (y + size_t{size[1]} * z);
          if (!valid[at]) (*x)[at] = sparse[i + px * y + pxy * z];
        }
    analyzeSamples(plan, size, *x, coefficients);
  }
}

}  // namespace mrsv
