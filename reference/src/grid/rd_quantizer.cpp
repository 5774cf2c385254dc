// Rate-distortion optimised quantisation (informative 5.9): the block walk and
// the contexts of codeArray() (spec 5.7.2, 5.7.3), with bit costs taken from
// the adaptive models instead of a range coder.
#include "grid/rd_quantizer.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrsv {
namespace {

// -log2 of the probability of bit b under a model holding p0 (spec 5.6).
struct BitCosts {
  float bits[2][kProbabilityOne];
  BitCosts() {
    for (int p = 0; p < kProbabilityOne; ++p) {
      const double p0 = std::max(p, 1) / double{kProbabilityOne};
      bits[0][p] = static_cast<float>(-std::log2(p0));
      bits[1][p] = static_cast<float>(-std::log2(std::max(1.0 / kProbabilityOne, 1.0 - p0)));
    }
  }
};
const BitCosts& bitCosts() {
  static const BitCosts costs;
  return costs;
}

// One adaptive bit: its cost, and with kCommit the model's update (the
// encoder's adaptation, range_encoder.h).
template <bool kCommit>
double codeBit(BitModel* m, int b) {
  const double bits = bitCosts().bits[b][m->p0];
  if (kCommit) {
    if (b == 0)
      m->p0 = static_cast<uint16_t>(m->p0 + ((kProbabilityOne - m->p0) >> kAdaptShift));
    else
      m->p0 = static_cast<uint16_t>(m->p0 - (m->p0 >> kAdaptShift));
  }
  return bits;
}

// The bits of symbol `mag` (sign `negative`) in class `cls` after a left
// neighbour `left` (spec 5.7.3 steps 2 to 5); with kCommit the models adapt.
template <bool kCommit>
double symbolBits(ArrayContexts& ctx, int cls, int64_t left, uint64_t mag, bool negative) {
  if (mag == 0) return codeBit<kCommit>(&ctx.zero[cls], 0);
  double bits = codeBit<kCommit>(&ctx.zero[cls], 1);
  bits += codeBit<kCommit>(&ctx.sign[left == 0 ? 0 : left > 0 ? 1 : 2], negative);
  int length = 0;  // floor(log2(mag)): ones of the unary prefix
  while ((mag >> (length + 1)) != 0) ++length;
  for (int j = 0; j <= length; ++j)
    bits += codeBit<kCommit>(&ctx.magnitude[cls][std::min(j, kMagnitudeModels - 1)], j < length);
  if (length > 0) {
    const int below = static_cast<int>((mag >> (length - 1)) & 1);
    bits += codeBit<kCommit>(&ctx.first_low_bit[cls][std::min(length, kMagnitudeModels - 1)], below);
    bits += length - 1;  // equiprobable (decode_direct)
  }
  return bits;
}

}  // namespace

bool rdQuantizeArray(const double* scaled, const ArrayBox& box, double lambda, int64_t q_limit,
                     int64_t* q) {
  ArrayContexts ctx;
  const uint32_t edge = blockEdge(box.num_dims);
  const uint32_t bx = (box.size[0] + edge - 1) / edge;
  const uint32_t by = box.num_dims >= 2 ? (box.size[1] + edge - 1) / edge : 1;
  const uint32_t bz = box.num_dims >= 3 ? (box.size[2] + edge - 1) / edge : 1;
  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  std::vector<uint8_t> nonzero(size_t{bx} * by * bz, 0);
  bool any = false;
  for (uint32_t kz = 0; kz < bz; ++kz)
    for (uint32_t ky = 0; ky < by; ++ky)
      for (uint32_t kx = 0; kx < bx; ++kx) {
        const uint32_t x0 = kx * edge, y0 = ky * edge, z0 = kz * edge;
        const uint32_t x1 = std::min(box.size[0], x0 + edge);
        const uint32_t y1 = box.num_dims >= 2 ? std::min(box.size[1], y0 + edge) : 1;
        const uint32_t z1 = box.num_dims >= 3 ? std::min(box.size[2], z0 + edge) : 1;
        const size_t b = kx + size_t{bx} * (ky + size_t{by} * kz);
        BitModel* flag = &ctx.block[(kx > 0 && nonzero[b - 1]) | ((ky > 0 && nonzero[b - bx]) << 1) |
                                    ((kz > 0 && nonzero[b - size_t{bx} * by]) << 2)];
        // The block coded as it is decided position by position, against the
        // block flagged zero: costs in squared steps plus lambda per bit.
        const ArrayContexts before = ctx;
        double coded_cost = lambda * codeBit<false>(flag, 1), zero_cost = lambda * codeBit<false>(flag, 0);
        bool block_any = false;
        for (uint32_t z = z0; z < z1; ++z)
          for (uint32_t y = y0; y < y1; ++y) {
            const size_t start = y * sx + z * sxy;
            int64_t* row = q + start;
            const int64_t* up = y > 0 ? row - sx : nullptr;
            const int64_t* back = z > 0 ? row - sxy : nullptr;
            const uint32_t up_right_end = y > y0 ? x1 : box.size[0];  // as in codeArray()
            for (uint32_t x = x0; x < x1; ++x) {
              const int64_t left = x > 0 ? row[x - 1] : 0;
              uint64_t around = 2 * magnitudeOf(left);
              if (up) {
                around += 2 * magnitudeOf(up[x]);
                if (x > 0) around += magnitudeOf(up[x - 1]);
                if (x + 1 < up_right_end) around += magnitudeOf(up[x + 1]);
              }
              if (back) around += 2 * magnitudeOf(back[x]);
              const int cls = magnitudeClass(around);
              const double c = scaled[start + x], a = std::fabs(c);
              const bool negative = c < 0;
              const uint64_t nearest = static_cast<uint64_t>(std::min<double>(std::floor(a + 0.5), double(q_limit)));
              uint64_t best = 0;
              double best_cost = a * a + lambda * symbolBits<false>(ctx, cls, left, 0, false);
              for (uint64_t m = nearest; m > 0 && m + 2 > nearest; --m) {
                const double e = a - static_cast<double>(m);
                const double cost = e * e + lambda * symbolBits<false>(ctx, cls, left, m, negative);
                if (cost < best_cost) best_cost = cost, best = m;
              }
              symbolBits<true>(ctx, cls, left, best, negative);
              row[x] = negative ? -static_cast<int64_t>(best) : static_cast<int64_t>(best);
              coded_cost += best_cost;
              zero_cost += a * a;
              block_any |= best != 0;
            }
          }
        if (!block_any || zero_cost <= coded_cost) {
          ctx = before;  // no symbol of the block is coded
          for (uint32_t z = z0; z < z1; ++z)
            for (uint32_t y = y0; y < y1; ++y) std::fill(q + y * sx + z * sxy + x0, q + y * sx + z * sxy + x1, 0);
        } else {
          nonzero[b] = 1;
          any = true;
        }
        codeBit<true>(flag, nonzero[b]);
      }
  return any;
}

}  // namespace mrsv
