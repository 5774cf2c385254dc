// Rate-distortion optimised quantisation (informative 5.9): the block walk and
// the contexts of codeArray() (spec 5.7.2, 5.7.3), each symbol priced by
// codeSymbol() itself with a coder that counts bits instead of writing them.
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
double bitCost(const BitModel* m, int b) {
  static const BitCosts costs;
  return costs.bits[b][m->p0];
}

// -log2 of the probability of a symbol whose interval is w of 2^15 wide.
struct SymbolCosts {
  float bits[(1u << kSymbolBits) + 1];
  SymbolCosts() {
    for (uint32_t w = 0; w <= 1u << kSymbolBits; ++w)
      bits[w] = static_cast<float>(kSymbolBits - std::log2(std::max<uint32_t>(w, 1)));
  }
};
double symbolCost(const SymbolModel* m, int s) {
  static const SymbolCosts costs;
  return costs.bits[m->width(s)];
}

// A coder for codeSymbol() and codeArray()'s shape (range_coder_adapter.h) that
// writes nothing: it adds up -log2 of each bit's and symbol's probability and, with
// kCommit, adapts the models as the range encoder does. So the costs follow
// the coding of 5.7.3 (up to the rounding of the intervals to the range).
template <bool kCommit>
struct CostCoder {
  static constexpr bool kEncoding = true;
  double bits = 0;
  int bit(BitModel* m, int b) {
    bits += bitCost(m, b);
    if (kCommit) {
      if (b == 0)
        m->p0 = static_cast<uint16_t>(m->p0 + ((kProbabilityOne - m->p0) >> kAdaptShift));
      else
        m->p0 = static_cast<uint16_t>(m->p0 - (m->p0 >> kAdaptShift));
    }
    return b;
  }
  int symbol(SymbolModel* m, int s) {
    bits += symbolCost(m, s);
    if (kCommit) m->adapt(s);
    return s;
  }
  uint32_t direct(uint32_t value, int n) {
    bits += n;  // equiprobable (decode_direct)
    return value;
  }
};

// The bits of symbol `sym` after a left neighbour `left`, with `around` the
// neighbours' weighted magnitudes (spec 5.7.3); with kCommit the models adapt.
template <bool kCommit>
double symbolBits(ArrayContexts& ctx, int64_t left, uint64_t around, int64_t sym) {
  CostCoder<kCommit> coder;
  codeSymbol(coder, ctx, left, around, &sym);
  return coder.bits;
}

}  // namespace

bool rdQuantizeArray(const double* scaled, const ArrayBox& box, double lambda, int64_t q_limit,
                     int64_t* q) {
  ArrayContexts ctx;
  const BlockGrid blocks(box);
  const uint32_t edge = blocks.edge;
  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  std::vector<uint8_t> nonzero(blocks.total(), 0);
  bool any = false;
  for (uint32_t kz = 0; kz < blocks.count[2]; ++kz)
    for (uint32_t ky = 0; ky < blocks.count[1]; ++ky)
      for (uint32_t kx = 0; kx < blocks.count[0]; ++kx) {
        const uint32_t x0 = kx * edge, y0 = ky * edge, z0 = kz * edge;
        const uint32_t x1 = blocks.end(0, kx), y1 = blocks.end(1, ky), z1 = blocks.end(2, kz);
        const size_t b = blocks.index(kx, ky, kz);
        BitModel* flag = &ctx.block[blocks.flagContext(nonzero.data(), kx, ky, kz)];
        // The block coded as it is decided position by position, against the
        // block flagged zero: costs in squared steps plus lambda per bit.
        const ArrayContexts before = ctx;
        double coded_cost = lambda * bitCost(flag, 1), zero_cost = lambda * bitCost(flag, 0);
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
              const double c = scaled[start + x], a = std::fabs(c);
              const int64_t sign = c < 0 ? -1 : 1;
              const int64_t nearest = static_cast<int64_t>(std::min<double>(std::floor(a + 0.5), double(q_limit)));
              int64_t best = 0;
              double best_cost = a * a + lambda * symbolBits<false>(ctx, left, around, 0);
              for (int64_t m = nearest; m > 0 && m + 2 > nearest; --m) {
                const double e = a - static_cast<double>(m);
                const double cost = e * e + lambda * symbolBits<false>(ctx, left, around, sign * m);
                if (cost < best_cost) best_cost = cost, best = m;
              }
              row[x] = sign * best;
              symbolBits<true>(ctx, left, around, row[x]);
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
        CostCoder<true>().bit(flag, nonzero[b]);
      }
  return any;
}

}  // namespace mrsv
