// Context modelling of integer arrays (quantised bands, residuals). spec: 5.7.
//
// One template walks an array and decides every binary symbol and its
// context; it is instantiated with the range decoder (normative) and with the
// range encoder, so that the two cannot drift apart. In encoding mode the
// values are read from `values`; in decoding mode they are written there.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "bitstream/range_decoder.h"

namespace mrsv {

// The box of an array: x fastest, then y, then z; unused axes have size 1.
struct ArrayBox {
  uint32_t size[3] = {1, 1, 1};
  int num_dims = 1;
  uint64_t count() const { return uint64_t{size[0]} * size[1] * size[2]; }
};

// spec: 5.7.1 coding modes of an array.
enum class ArrayPrediction : uint8_t {
  kNone = 0,      // values coded as they are (detail bands, residuals)
  kNeighbour = 1, // each value coded as the difference to a prediction from its
                  // decoded neighbours (the coarsest scaling block)
  kWeighted = 2,  // weighted prediction with its own contexts (spec 5.7.5,
                  // weighted_array_coding.h; codeArray never sees it)
};

constexpr int kMagnitudeClasses = 10;
constexpr int kMagnitudeModels = 12;
constexpr int kMaxMagnitudeBits = 40;  // coded symbols satisfy |s| < 2^39 + 15 < 2^40
// spec: 5.7.4 decoded values are clamped to +-kArrayValueLimit, so that garbage
// cannot grow through the predictor; an encoder never needs the clamp.
constexpr int64_t kArrayValueLimit = (int64_t{1} << 40) - 1;

inline int64_t clampArrayValue(int64_t v) {
  return v > kArrayValueLimit ? kArrayValueLimit : v < -kArrayValueLimit ? -kArrayValueLimit : v;
}

struct ArrayContexts {
  BitModel block[8];
  BitModel zero[kMagnitudeClasses];
  BitModel sign[3];
  SymbolModel level[kMagnitudeClasses];
  BitModel magnitude[kMagnitudeClasses][kMagnitudeModels];
  BitModel first_low_bit[kMagnitudeClasses][kMagnitudeModels];
};

// spec: 5.7.2 block edge per dimensionality: 64 samples (1-D), 8x8 (2-D), 4x4x4 (3-D).
inline uint32_t blockEdge(int num_dims) { return num_dims == 1 ? 64 : num_dims == 2 ? 8 : 4; }

// spec: 5.7.2 the blocks of an array: how many along each axis, where block
// (kx, ky, kz) ends along each axis (the last one of an axis may be short),
// and the context of its flag from the flags, in raster order, of the blocks
// before it along x, y and z. Every walk of the blocks (codeArray(), the
// decoder's decodeUnpredictedArray(), the encoder's rdQuantizeArray()) uses it.
struct BlockGrid {
  uint32_t edge, size[3], count[3];
  explicit BlockGrid(const ArrayBox& box) : edge(blockEdge(box.num_dims)) {
    for (int a = 0; a < 3; ++a) {
      size[a] = a < box.num_dims ? box.size[a] : 1;
      count[a] = (size[a] + edge - 1) / edge;
    }
  }
  size_t total() const { return size_t{count[0]} * count[1] * count[2]; }
  size_t index(uint32_t kx, uint32_t ky, uint32_t kz) const {
    return kx + size_t{count[0]} * (ky + size_t{count[1]} * kz);
  }
  // One past the last position of block k along axis a.
  uint32_t end(int a, uint32_t k) const {
    const uint32_t e = (k + 1) * edge;
    return size[a] < e ? size[a] : e;
  }
  int flagContext(const uint8_t* nonzero, uint32_t kx, uint32_t ky, uint32_t kz) const {
    const size_t b = index(kx, ky, kz);
    return (kx > 0 && nonzero[b - 1]) | ((ky > 0 && nonzero[b - count[0]]) << 1) |
           ((kz > 0 && nonzero[b - size_t{count[0]} * count[1]]) << 2);
  }
};

// spec: 5.7.3 magnitude class from the weighted sum of the neighbours'
// magnitudes: 0 for 0, then one class per doubling (1-2, 3-4, 5-8, ...).
// Class kMagnitudeClasses - 1 = 9 takes every sum above 256; below, a table
// (built by the rule itself) replaces a loop whose exit is hard to predict.
struct MagnitudeClassTable {
  static constexpr uint64_t kLast = 256;  // the largest sum of class 8
  uint8_t cls[kLast + 1];
  constexpr MagnitudeClassTable() : cls() {
    int c = 0;
    uint64_t bound = 0;
    for (uint64_t s = 0; s <= kLast; ++s) {
      while (c < kMagnitudeClasses - 1 && s > bound) {
        ++c;
        bound = bound == 0 ? 2 : 2 * bound;
      }
      cls[s] = static_cast<uint8_t>(c);
    }
  }
};
inline constexpr MagnitudeClassTable kMagnitudeClassTable{};
static_assert(kMagnitudeClassTable.cls[MagnitudeClassTable::kLast] == kMagnitudeClasses - 2 &&
                  kMagnitudeClassTable.cls[1] == 1 && kMagnitudeClassTable.cls[3] == 2,
              "classes 1..8 end at 2, 4, ..., 256");

inline int magnitudeClass(uint64_t s) {
  return s > MagnitudeClassTable::kLast ? kMagnitudeClasses - 1 : kMagnitudeClassTable.cls[s];
}

inline uint64_t magnitudeOf(int64_t v) {
  return v < 0 ? uint64_t(0) - static_cast<uint64_t>(v) : static_cast<uint64_t>(v);
}

inline int64_t medianPredictor(int64_t a, int64_t b, int64_t c) {
  int64_t lo = a < b ? a : b, hi = a < b ? b : a;
  if (c >= hi) return lo;
  if (c <= lo) return hi;
  return a + b - c;
}

// spec: 5.7.4 prediction of value (x, y, z) from decoded values of the array.
inline int64_t predictNeighbour(const int64_t* v, const ArrayBox& box, uint32_t x, uint32_t y,
                                uint32_t z) {
  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  const size_t i = x + y * sx + z * sxy;
  auto at = [&](size_t dx, size_t dy, size_t dz) { return v[i - dx - dy * sx - dz * sxy]; };
  if (z == 0) {
    if (x > 0 && y > 0) return medianPredictor(at(1, 0, 0), at(0, 1, 0), at(1, 1, 0));
    if (x > 0) return at(1, 0, 0);
    if (y > 0) return at(0, 1, 0);
    return 0;
  }
  // Lorenzo predictor: exact on trilinear data; seven terms below 2^40, no overflow.
  if (x > 0 && y > 0)
    return at(1, 0, 0) + at(0, 1, 0) + at(0, 0, 1) - at(1, 1, 0) - at(1, 0, 1) - at(0, 1, 1) +
           at(1, 1, 1);
  if (x > 0) return at(1, 0, 0) + at(0, 0, 1) - at(1, 0, 1);
  if (y > 0) return at(0, 1, 0) + at(0, 0, 1) - at(0, 1, 1);
  return at(0, 0, 1);
}

// spec: 5.7.3 step 5, a magnitude's part e >= 1 above the escape as an
// Elias-gamma-like code: n = floor(log2(e)) in adaptive unary, the bit below
// the leading one adaptive, the other n - 1 bits equiprobable in groups of at
// most 24. Returns false when a decoded prefix reaches kMaxMagnitudeBits - 1.
template <class Coder>
bool codeEscape(Coder& coder, ArrayContexts& ctx, int cls, uint64_t* e) {
  const uint64_t value = Coder::kEncoding ? *e : 0;
  int length = 0;  // floor(log2(e))
  if (Coder::kEncoding)
    while ((value >> (length + 1)) != 0) ++length;
  int n = 0;
  while (true) {
    BitModel* m = &ctx.magnitude[cls][n < kMagnitudeModels ? n : kMagnitudeModels - 1];
    if (coder.bit(m, n < length) == 0) break;
    if (++n == kMaxMagnitudeBits - 1) return false;
  }
  uint64_t low = 0;
  int done = 0;
  if (n > 0) {
    BitModel* m = &ctx.first_low_bit[cls][n < kMagnitudeModels ? n : kMagnitudeModels - 1];
    low = static_cast<uint64_t>(coder.bit(m, static_cast<int>((value >> (n - 1)) & 1)));
    done = 1;
  }
  while (done < n) {
    int chunk = n - done > 24 ? 24 : n - done;
    uint32_t part = static_cast<uint32_t>((value >> (n - done - chunk)) & ((1u << chunk) - 1));
    low = (low << chunk) | coder.direct(part, chunk);
    done += chunk;
  }
  *e = (uint64_t{1} << n) | low;
  return true;
}

// Magnitudes 1 to 15 are the symbols 0 to 14 of one 16-ary model per class;
// symbol 15 is the escape to codeEscape() with e = |s| - 15.
constexpr uint64_t kEscapeSymbol = kSymbolCount - 1;

// The sign and magnitude of a nonzero symbol *sym (spec 5.7.3 steps 3 to 6), in
// magnitude class `cls`. Returns false when a decoded magnitude prefix is longer
// than kMaxMagnitudeBits - 1.
template <class Coder>
bool codeNonzeroSymbol(Coder& coder, ArrayContexts& ctx, int cls, int64_t left, int64_t* sym) {
  const int64_t value = Coder::kEncoding ? *sym : 0;
  const uint64_t mag = magnitudeOf(value);
  const int sign_ctx = left == 0 ? 0 : left > 0 ? 1 : 2;
  const int negative = coder.bit(&ctx.sign[sign_ctx], value < 0);
  const uint64_t level = static_cast<uint64_t>(
      coder.symbol(&ctx.level[cls], static_cast<int>(mag - 1 < kEscapeSymbol ? mag - 1 : kEscapeSymbol)));
  uint64_t decoded = level + 1;
  if (level == kEscapeSymbol) {
    uint64_t e = mag - kEscapeSymbol;
    if (!codeEscape(coder, ctx, cls, &e)) return false;
    decoded = e + kEscapeSymbol;
  }
  *sym = negative ? -static_cast<int64_t>(decoded) : static_cast<int64_t>(decoded);
  return true;
}

// Codes one value's symbol *sym (the value or its prediction residual) given
// `left`, the symbol at x - 1, and `around`, the weighted sum of the
// neighbours' magnitudes (spec 5.7.3). Most symbols are 0 and end at the first
// bit, so that part is kept apart from the rest. Returns false when a decoded
// magnitude prefix is longer than kMaxMagnitudeBits - 1.
template <class Coder>
bool codeSymbol(Coder& coder, ArrayContexts& ctx, int64_t left, uint64_t around, int64_t* sym) {
  const int cls = magnitudeClass(around);
  if (coder.bit(&ctx.zero[cls], Coder::kEncoding && *sym != 0) == 0) {
    *sym = 0;
    return true;
  }
  return codeNonzeroSymbol(coder, ctx, cls, left, sym);
}

// spec: 5.7 array(): codes every value of `values` over `box`, block by block.
// `skip` (may be null) marks positions that are not coded and hold 0 (an
// encoder must pass 0 there too, since predictions read them).
// `symbols` is scratch of box.count() entries, its contents on entry unused (a
// symbol is read only after it is coded); without prediction it may be `values`
// itself. Returns false on a decoding error.
template <class Coder>
bool codeArray(Coder& coder, int64_t* values, int64_t* symbols, const ArrayBox& box,
               ArrayPrediction prediction, const uint8_t* skip) {
  ArrayContexts ctx;
  const BlockGrid blocks(box);
  const uint32_t edge = blocks.edge;
  const uint32_t size_x = box.size[0];
  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  // One flag per block: nonzero[] of the previous block row and slice give contexts.
  uint8_t* nonzero = static_cast<uint8_t*>(std::calloc(blocks.total(), 1));
  if (!nonzero) return false;
  bool ok = true;
  for (uint32_t kz = 0; kz < blocks.count[2] && ok; ++kz)
    for (uint32_t ky = 0; ky < blocks.count[1] && ok; ++ky)
      for (uint32_t kx = 0; kx < blocks.count[0] && ok; ++kx) {
        const uint32_t x0 = kx * edge, y0 = ky * edge, z0 = kz * edge;
        const uint32_t x1 = blocks.end(0, kx), y1 = blocks.end(1, ky), z1 = blocks.end(2, kz);
        const size_t b = blocks.index(kx, ky, kz);
        if (Coder::kEncoding) {
          for (uint32_t z = z0; z < z1; ++z)
            for (uint32_t y = y0; y < y1; ++y)
              for (uint32_t x = x0; x < x1; ++x) {
                size_t i = x + y * sx + z * sxy;
                int64_t s = values[i];
                if (prediction == ArrayPrediction::kNeighbour) s -= predictNeighbour(values, box, x, y, z);
                if (skip && skip[i]) s = 0;
                symbols[i] = s;
                if (s != 0) nonzero[b] = 1;
              }
        }
        const int c = blocks.flagContext(nonzero, kx, ky, kz);
        nonzero[b] = static_cast<uint8_t>(coder.bit(&ctx.block[c], nonzero[b]));
        if (!nonzero[b] && prediction == ArrayPrediction::kNone) {
          // No symbol is coded in the block: every symbol (and decoded value) is 0.
          for (uint32_t z = z0; z < z1; ++z)
            for (uint32_t y = y0; y < y1; ++y) {
              const size_t start = y * sx + z * sxy;
              for (uint32_t x = x0; x < x1; ++x) {
                symbols[start + x] = 0;
                if (!Coder::kEncoding) values[start + x] = 0;
              }
            }
          continue;
        }
        // A local flag, not nonzero[b]: the stores below could alias a byte array,
        // which would force a reload at every position.
        const bool coded = nonzero[b] != 0;
        for (uint32_t z = z0; z < z1 && ok; ++z)
          for (uint32_t y = y0; y < y1 && ok; ++y) {
            const size_t start = y * sx + z * sxy;
            int64_t* row = symbols + start;
            int64_t* value_row = values + start;
            const uint8_t* skip_row = skip ? skip + start : nullptr;
            const int64_t* up = y > 0 ? row - sx : nullptr;
            const int64_t* back = z > 0 ? row - sxy : nullptr;
            // The neighbour above to the right (spec 5.7.3) of the row's last
            // position is in the next block; within this block's rows (y > y0)
            // that block is not coded yet and the neighbour counts as 0.
            const uint32_t up_right_end = y > y0 ? x1 : size_x;
            // The neighbours of position x, moved along the row: the symbol at
            // x - 1 and the magnitudes above at x - 1, x (and x + 1 just below;
            // it is 0 by the rule above only at the row's last position).
            int64_t left = x0 > 0 ? row[x0 - 1] : 0;
            uint64_t up_left = up && x0 > 0 ? magnitudeOf(up[x0 - 1]) : 0;
            uint64_t up_mid = up ? magnitudeOf(up[x0]) : 0;
            for (uint32_t x = x0; x < x1; ++x) {
              const uint64_t up_right = up && x + 1 < up_right_end ? magnitudeOf(up[x + 1]) : 0;
              if (!coded || (skip_row && skip_row[x])) {
                row[x] = 0;
              } else {
                uint64_t around = 2 * magnitudeOf(left) + 2 * up_mid + up_left + up_right;
                if (back) around += 2 * magnitudeOf(back[x]);
                if (!codeSymbol(coder, ctx, left, around, &row[x])) {
                  ok = false;
                  break;
                }
              }
              left = row[x];
              up_left = up_mid;
              up_mid = up_right;
              if (!Coder::kEncoding) {
                value_row[x] = left;
                if (prediction == ArrayPrediction::kNeighbour && !(skip_row && skip_row[x]))
                  value_row[x] =
                      clampArrayValue(value_row[x] + predictNeighbour(values, box, x, y, z));
              }
            }
          }
      }
  std::free(nonzero);
  return ok;
}

// Adapters giving both coders the same shape for codeArray.
}  // namespace mrsv
