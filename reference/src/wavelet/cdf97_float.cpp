// spec: 4.11 (informative part) real-valued CDF 9/7 analysis and synthesis,
// the exact inverse pair that the fixed-point synthesis of 4.11.3 rounds.
#include <cstddef>

#include "wavelet/cdf97.h"

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

}  // namespace

void analyzeCdf97Lines(double* x, double* out, size_t len, int width) {
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

void synthesizeCdf97Lines(const double* in, double* x, size_t len, int width) {
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

}  // namespace mrsv::wavelet
