// Arrays coded with weighted prediction (prediction 2). spec: 5.7.5.
//
// Every value is predicted by the weighted predictor and its residual coded
// with its own contexts: a class from the neighbours' residual magnitudes in
// half-doubling steps, a sign context from the predictor's recent errors, and
// the two bits below the leading one adaptive. There are no block flags: the
// mode is meant for the samples themselves, where nearly every residual is
// non-zero. Like codeArray, one template serves the decoder and the encoder.
#pragma once

#include <cstdint>

#include "grid/coefficient_coding.h"
#include "grid/weighted_predictor.h"

namespace mrsv {

constexpr int kWeightedClasses = 20;

struct WeightedContexts {
  BitModel zero[kWeightedClasses];
  BitModel sign[kWeightedClasses][3];
  BitModel magnitude[kWeightedClasses][kMagnitudeModels];
  BitModel first_low_bit[kWeightedClasses][kMagnitudeModels];
  BitModel second_low_bit[kWeightedClasses][kMagnitudeModels][2];
};

// spec: 5.7.5 the class of a: a itself below 2, then two classes per doubling
// (2L + the bit below the leading one, L = floor(log2 a)), at most 19.
inline int weightedClass(uint64_t a) {
  if (a < 2) return static_cast<int>(a);
  int length = 63 - __builtin_clzll(a);
  int k = 2 * length + static_cast<int>((a >> (length - 1)) & 1);
  return k < kWeightedClasses - 1 ? k : kWeightedClasses - 1;
}

// One symbol (spec 5.7.5 steps 2 to 5). Returns false when a decoded
// magnitude prefix is longer than kMaxMagnitudeBits - 1.
template <class Coder>
bool codeWeightedSymbol(Coder& coder, WeightedContexts& ctx, int k, int t, int64_t* sym) {
  const int64_t value = Coder::kEncoding ? *sym : 0;
  if (coder.bit(&ctx.zero[k], value != 0) == 0) {
    *sym = 0;
    return true;
  }
  const uint64_t mag = magnitudeOf(value);
  // The sign and the two bits below the leading one are hard for a branch
  // predictor: decoded without a branch on the outcome (bitUnpredictable).
  const int negative = coder.bitUnpredictable(&ctx.sign[k][t], value < 0);
  int length = 0;  // floor(log2(|s|))
  if (Coder::kEncoding)
    while ((mag >> (length + 1)) != 0) ++length;
  int n = 0;
  while (true) {
    BitModel* m = &ctx.magnitude[k][n < kMagnitudeModels ? n : kMagnitudeModels - 1];
    if (coder.bit(m, n < length) == 0) break;
    if (++n == kMaxMagnitudeBits - 1) return false;
  }
  const int model = n < kMagnitudeModels ? n : kMagnitudeModels - 1;
  uint64_t low = 0;
  int done = 0;
  // Residuals are roughly Laplacian, so the two bits below the leading one
  // are skewed towards 0; the rest are nearly equiprobable.
  if (n >= 1) {
    low = static_cast<uint64_t>(
        coder.bitUnpredictable(&ctx.first_low_bit[k][model], static_cast<int>((mag >> (n - 1)) & 1)));
    done = 1;
  }
  if (n >= 2) {
    const int h = static_cast<int>(low);
    low = (low << 1) |
          static_cast<uint64_t>(
              coder.bitUnpredictable(&ctx.second_low_bit[k][model][h], static_cast<int>((mag >> (n - 2)) & 1)));
    done = 2;
  }
  while (done < n) {
    int chunk = n - done > 24 ? 24 : n - done;
    uint32_t part = static_cast<uint32_t>((mag >> (n - done - chunk)) & ((1u << chunk) - 1));
    low = (low << chunk) | coder.direct(part, chunk);
    done += chunk;
  }
  const uint64_t decoded = (uint64_t{1} << n) | low;
  *sym = negative ? -static_cast<int64_t>(decoded) : static_cast<int64_t>(decoded);
  return true;
}

// spec: 5.7.5 codes every value of `values` over `box` in raster order, slice
// by slice; `symbols` is scratch of 2 * box.size[0] entries (the contexts read
// the symbols of the row and of the row above). Returns false on a decoding
// error or when memory runs out.
template <class Coder>
bool codeWeightedArray(Coder& coder, int64_t* values, int64_t* symbols, const ArrayBox& box) {
  WeightedContexts ctx;
  WeightedPredictor predictor;
  const uint32_t size_x = box.size[0];
  if (!predictor.init(size_x)) return false;
  const size_t sx = size_x, sxy = size_t{size_x} * box.size[1];
  for (uint32_t z = 0; z < box.size[2]; ++z)
    for (uint32_t y = 0; y < box.size[1]; ++y) {
      int64_t* row = values + y * sx + z * sxy;
      int64_t* sym_row = symbols + (y & 1) * sx;
      const int64_t* up = y > 0 ? row - sx : nullptr;
      const int64_t* up2 = y > 1 ? row - 2 * sx : nullptr;
      const int64_t* sym_up = y > 0 ? symbols + ((y - 1) & 1) * sx : nullptr;
      for (uint32_t x = 0; x < size_x; ++x) {
        // a = 2|l| + 2|u| + |ul| + |ur| over the slice's residuals.
        uint64_t a = 0;
        if (x > 0) a += 2 * magnitudeOf(sym_row[x - 1]);
        if (sym_up) {
          a += 2 * magnitudeOf(sym_up[x]);
          if (x > 0) a += magnitudeOf(sym_up[x - 1]);
          if (x + 1 < size_x) a += magnitudeOf(sym_up[x + 1]);
        }
        const int64_t p = predictor.predict(row, up, up2, x);
        int64_t s = Coder::kEncoding ? row[x] - p : 0;
        if (!codeWeightedSymbol(coder, ctx, weightedClass(a), predictor.signContext(), &s))
          return false;
        sym_row[x] = s;
        if (!Coder::kEncoding) row[x] = clampArrayValue(s + p);
        predictor.record(x, row[x]);
      }
      predictor.nextRow();
    }
  return true;
}

}  // namespace mrsv
