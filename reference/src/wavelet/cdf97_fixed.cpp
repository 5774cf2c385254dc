// spec: 4.11.3 fixed-point synthesis of the CDF 9/7 wavelet. Decode side:
// integers only.
#include <cstddef>
#include <vector>

#include "wavelet/cdf97.h"
#include "wavelet/line_batches.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv::wavelet {
namespace {

constexpr int64_t kHalf = int64_t{1} << (kCdf97FracBits - 1);

int64_t sat(int64_t v) { return v > kValueLimit ? kValueLimit : v < -kValueLimit ? -kValueLimit : v; }

// floor((c * v + 2^23) / 2^24); |c * v| < 2^60.7 (4.11.4). C++17 leaves >> of a
// negative value to the implementation; every compiler we build with shifts
// arithmetically (checked below), and a branch on the sign here would be
// mispredicted about half the time.
static_assert((int64_t{-3} >> 1) == -2, "the 9/7 synthesis needs an arithmetic right shift");
int64_t scaled(int64_t c, int64_t v) { return (c * v + kHalf) >> kCdf97FracBits; }

// One lifting step undone over a batch of `width` interleaved lines of `len`
// values: x[p] -= c * (x[p-1] + x[p+1]) for every p of `parity`, the
// neighbours mirrored at the ends (x[-1] = x[1], x[len] = x[len-2]).
void unlift(int64_t* x, size_t len, int width, size_t parity, int64_t c) {
  const size_t w = static_cast<size_t>(width);
  for (size_t p = parity; p < len; p += 2) {
    const int64_t* left = x + (p > 0 ? p - 1 : p + 1) * w;
    const int64_t* right = x + (p + 1 < len ? p + 1 : p - 1) * w;
    int64_t* out = x + p * w;
    for (size_t k = 0; k < w; ++k) out[k] = sat(out[k] - scaled(c, left[k] + right[k]));
  }
}

// One level along one axis for a batch of lines (line_batches.h layout): the
// low half [0, h) and the high half [h, len) interleaved back into even and
// odd positions, the low values scaled by K, then the four lifting steps
// undone in reverse order (spec 4.11.3).
void synthesizeBatch(const int64_t* in, int64_t* x, size_t len, int width) {
  const size_t w = static_cast<size_t>(width), h = (len + 1) / 2;
  for (size_t i = 0; i < h; ++i)
    for (size_t k = 0; k < w; ++k) x[2 * i * w + k] = sat(scaled(kCdf97K, sat(in[i * w + k])));
  for (size_t i = 0; i + h < len; ++i)
    for (size_t k = 0; k < w; ++k) x[(2 * i + 1) * w + k] = sat(in[(h + i) * w + k]);
  unlift(x, len, width, 0, kCdf97Delta);
  unlift(x, len, width, 1, kCdf97Gamma);
  unlift(x, len, width, 0, kCdf97Beta);
  unlift(x, len, width, 1, kCdf97Alpha);
}

}  // namespace

void synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level) {
  if (!isValidGridPlan(plan)) return;
  if (stop_level < 0) stop_level = 0;
  const uint32_t padded[3] = {plan.axis[0].size(0), plan.axis[1].size(0), plan.axis[2].size(0)};
  std::vector<int64_t> in, out;
  for (int level = plan.maxLevels(); level > stop_level; --level) {
    uint32_t box[3];
    for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(level - 1);
    for (int a = 0; a < 3; ++a) {  // x, then y, then z (the order is normative: each pass rounds)
      if (plan.axis[a].levels < level) continue;
      forEachLineBatch(padded, box, a, data, &in, &out, [&](int64_t* src, int64_t* dst, int width) {
        synthesizeBatch(src, dst, box[a], width);
      });
    }
  }
}

}  // namespace mrsv::wavelet
