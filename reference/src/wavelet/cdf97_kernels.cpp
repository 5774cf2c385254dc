// spec: 4.11.3 the reference (scalar) arithmetic of the CDF 9/7 fixed-point
// synthesis, and the choice of the implementation the decoder runs.
#include "wavelet/cdf97_kernels.h"

#include "wavelet/cdf97.h"
#include "wavelet/synthesis_fixed.h"  // kValueLimit, saturate()

namespace mrsv::wavelet {
namespace {

constexpr int64_t kHalf = int64_t{1} << (kCdf97FracBits - 1);

// floor((c * v + 2^23) / 2^24); |c * v| < 2^60.7 (4.11.4). C++17 leaves >> of a
// negative value to the implementation; every compiler we build with shifts
// arithmetically (checked below), and a branch on the sign here would be
// mispredicted about half the time.
static_assert((int64_t{-3} >> 1) == -2, "the 9/7 synthesis needs an arithmetic right shift");
int64_t scaled(int64_t c, int64_t v) { return (c * v + kHalf) >> kCdf97FracBits; }

// 4.11.3: x[2i] = sat((sat(value i of the line) * K + 2^23) >> 24).
bool scaleScalar(const int64_t* x, int64_t* y, size_t n) {
  int64_t any = 0;
  for (size_t j = 0; j < n; ++j) any |= y[j] = saturate(scaled(kCdf97K, saturate(x[j])));
  return any != 0;
}

// 4.11.3: x[2i + 1] = sat(value h + i of the line).
bool saturateScalar(const int64_t* x, int64_t* y, size_t n) {
  int64_t any = 0;
  for (size_t j = 0; j < n; ++j) any |= y[j] = saturate(x[j]);
  return any != 0;
}

// 4.11.3 step(p, C): x[i] = sat(x[i] - ((C * (x[l] + x[r]) + 2^23) >> 24)).
void liftScalar(int64_t* y, const int64_t* a, const int64_t* b, size_t n, int64_t c) {
  for (size_t j = 0; j < n; ++j) y[j] = saturate(y[j] - scaled(c, a[j] + b[j]));
}

void interleaveScalar(const int64_t* even, const int64_t* odd, int64_t* out, size_t n_even,
                      size_t n_odd) {
  for (size_t j = 0; j < n_odd; ++j) {
    out[2 * j] = even[j];
    out[2 * j + 1] = odd[j];
  }
  if (n_even > n_odd) out[2 * n_odd] = even[n_odd];
}

}  // namespace

const Cdf97Kernels& cdf97ScalarKernels() {
  static const Cdf97Kernels kernels{scaleScalar, saturateScalar, liftScalar, interleaveScalar,
                                    "scalar"};
  return kernels;
}

const Cdf97Kernels& cdf97Kernels() {
  static const Cdf97Kernels& best = [] () -> const Cdf97Kernels& {
    if (const Cdf97Kernels* avx512 = cdf97Avx512Kernels()) return *avx512;
    if (const Cdf97Kernels* avx2 = cdf97Avx2Kernels()) return *avx2;
    return cdf97ScalarKernels();
  }();
  return best;
}

}  // namespace mrsv::wavelet
