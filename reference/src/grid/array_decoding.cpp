#include "grid/array_decoding.h"

#include <algorithm>
#include <cstdlib>
#include <type_traits>

#include "bitstream/range_coder_adapter.h"

namespace mrsv {
namespace {

// The contexts of spec 5.7.3 read the neighbours' magnitudes from an array of
// 16-bit entries, each capped at kMagnitudeCap: a neighbour above the cap puts
// the weighted sum above MagnitudeClassTable::kLast whether it is capped or
// not (every weight is at least 1), so the class does not change.
constexpr uint64_t kMagnitudeCap = MagnitudeClassTable::kLast + 1;
static_assert(kMagnitudeCap <= UINT16_MAX, "capped magnitudes fit 16 bits");

inline uint16_t cappedMagnitude(uint64_t m) {
  return static_cast<uint16_t>(m < kMagnitudeCap ? m : kMagnitudeCap);
}

// spec: 5.7.3 steps 3 to 6, the sign and magnitude of a symbol whose zero flag
// was 1, as codeNonzeroSymbol() decodes them; `left` gives the sign context by
// its sign. The symbol goes to *sym, its magnitude to *mag. False when the
// magnitude prefix reaches kMaxMagnitudeBits - 1 ones.
inline bool decodeNonzero(RangeDecoder& d, ArrayContexts& ctx, int cls, int64_t left,
                          int64_t* sym, uint64_t* mag) {
  // Context 0, 1, 2 for left = 0, > 0, < 0; computed, not branched on.
  const int negative = d.bitUnpredictable(&ctx.sign[(left != 0) + (left < 0)]);
  const uint64_t level = static_cast<uint64_t>(d.symbol(&ctx.level[cls]));
  uint64_t m = level + 1;
  if (level == kEscapeSymbol) {  // rare: the shared code, through the adapter
    DecodingCoder coder{&d};
    if (!codeEscape(coder, ctx, cls, &m)) return false;
    m += kEscapeSymbol;
  }
  // -m when negative, as (m XOR all ones) + 1: again no branch on a coin toss.
  const uint64_t flip = 0 - static_cast<uint64_t>(negative);
  *sym = static_cast<int64_t>((m ^ flip) - flip);
  *mag = m;
  return true;
}

template <bool B>
using Flag = std::integral_constant<bool, B>;

template <class T>
T* narrowed(const ArrayDestination& out);
template <>
int64_t* narrowed<int64_t>(const ArrayDestination& out) { return out.data; }
template <>
int16_t* narrowed<int16_t>(const ArrayDestination& out) { return out.narrow; }

// spec: 5.7.2 blocks in raster order, each with its flag; 5.7.3 the symbols of a
// flagged block. The walk is that of codeArray() with ArrayPrediction::kNone.
// T: int64_t, the values to out.data; int16_t, the symbols to out.narrow.
template <class T>
bool decodeArray(RangeDecoder* rc, const ArrayBox& box, const uint8_t* skip,
                 const ArrayDestination& out, uint16_t* magnitudes) {
  ArrayContexts ctx;
  // A copy in a local, written back at the end: its state can then stay in
  // registers, which a decoder reached through a pointer cannot.
  RangeDecoder d = *rc;
  const BlockGrid blocks(box);
  const uint32_t edge = blocks.edge;
  const uint32_t size_x = box.size[0];
  // `skip` and `magnitudes` are in the box's own raster order.
  const size_t sx = box.size[0], sxy = size_t{box.size[0]} * box.size[1];
  const size_t rs = out.row_stride, ss = out.slice_stride;
  // spec: 5.4 dequantisation, with the test for saturation hoisted; a value
  // that is its symbol is the same with step 1 and no limit.
  const uint64_t step = out.step;
  const int64_t signed_step = step == 0 ? 1 : static_cast<int64_t>(step);
  const uint64_t exact_limit =
      step == 0 ? UINT64_MAX : static_cast<uint64_t>(wavelet::kValueLimit) / step;
  auto valueOf = [&](int64_t sym, uint64_t mag) {
    return mag <= exact_limit ? sym * signed_step : dequantizeSymbol(sym, step);
  };
  T* const data = narrowed<T>(out);
  uint64_t all_magnitudes = 0;  // OR of them: below 2^15 when every symbol fits 16 bits

  // The positions [x0, x1) of one row of a flagged block: values to `row`,
  // capped magnitudes to `mag_row`. kUp, kBack: the row has a row above (y >
  // 0) and a slice behind (z > 0), at compile time so that the loop does not
  // test them. up_right_last: whether the last position's neighbour above to
  // the right (spec 5.7.3) is read. It lies in the next block: decoded when
  // the row is the block's first (y = y0), else not yet, and then 0.
  auto decodeRow = [&](auto up_flag, auto back_flag, T* row, uint16_t* mag_row,
                       const uint8_t* skip_row, uint32_t x0, uint32_t x1, bool up_right_last) {
    constexpr bool kUp = decltype(up_flag)::value, kBack = decltype(back_flag)::value;
    const uint16_t* up = kUp ? mag_row - sx : mag_row;
    const uint16_t* back = kBack ? mag_row - sxy : mag_row;
    // The neighbours of the next position, moved along the row: the symbol to
    // its left (its sign is all the sign context needs: the value's sign) and
    // the magnitudes to its left, above it and above to its left.
    int64_t left = 0;
    uint32_t left_mag = 0;
    if (x0 > 0) {
      const int64_t v = row[x0 - 1];
      left = (v > 0) - (v < 0);
      left_mag = mag_row[x0 - 1];
    }
    uint32_t up_left = kUp && x0 > 0 ? up[x0 - 1] : 0;
    uint32_t up_mid = kUp ? up[x0] : 0;
    for (uint32_t x = x0; x < x1; ++x) {
      // Read always and masked, not branched on (a branch mispredicted once
      // per row): up[x + 1] is at most the first entry of this row.
      uint32_t up_right = 0;
      if (kUp) up_right = up[x + 1] & (0u - ((x + 1 < x1) | up_right_last));
      int64_t sym = 0;
      uint64_t mag = 0;
      if (!(skip_row && skip_row[x])) {
        uint32_t around = 2 * left_mag + 2 * up_mid + up_left + up_right;
        if (kBack) around += 2 * uint32_t{back[x]};
        const int cls = magnitudeClass(around);
        if (d.bit(&ctx.zero[cls]) != 0 && !decodeNonzero(d, ctx, cls, left, &sym, &mag))
          return false;
      }
      if constexpr (sizeof(T) == sizeof(int64_t)) {
        row[x] = valueOf(sym, mag);
      } else {
        row[x] = static_cast<T>(sym);
        all_magnitudes |= mag;
      }
      left_mag = cappedMagnitude(mag);
      mag_row[x] = static_cast<uint16_t>(left_mag);
      left = sym;
      up_left = up_mid;
      up_mid = up_right;
    }
    return true;
  };

  if (out.narrow_fits) *out.narrow_fits = false;  // until the walk ends
  // One flag per block: those of the block before along x, y and z give the context.
  uint8_t* nonzero = static_cast<uint8_t*>(std::calloc(blocks.total(), 1));
  if (!nonzero) return false;
  bool ok = true;
  for (uint32_t kz = 0; kz < blocks.count[2] && ok; ++kz)
    for (uint32_t ky = 0; ky < blocks.count[1] && ok; ++ky)
      for (uint32_t kx = 0; kx < blocks.count[0] && ok; ++kx) {
        const uint32_t x0 = kx * edge, y0 = ky * edge, z0 = kz * edge;
        const uint32_t x1 = blocks.end(0, kx), y1 = blocks.end(1, ky), z1 = blocks.end(2, kz);
        const size_t b = blocks.index(kx, ky, kz);
        const int coded = d.bit(&ctx.block[blocks.flagContext(nonzero, kx, ky, kz)]);
        nonzero[b] = static_cast<uint8_t>(coded);
        for (uint32_t z = z0; z < z1 && ok; ++z)
          for (uint32_t y = y0; y < y1 && ok; ++y) {
            T* row = data + y * rs + z * ss;
            uint16_t* mag_row = magnitudes + y * sx + z * sxy;
            if (!coded) {  // every symbol of the block is 0
              std::fill(row + x0, row + x1, 0);
              std::fill(mag_row + x0, mag_row + x1, 0);
              continue;
            }
            const uint8_t* skip_row = skip ? skip + y * sx + z * sxy : nullptr;
            const bool up_right_last = y == y0 && x1 < size_x;
            if (y > 0) {
              ok = z > 0 ? decodeRow(Flag<true>(), Flag<true>(), row, mag_row, skip_row, x0, x1,
                                     up_right_last)
                         : decodeRow(Flag<true>(), Flag<false>(), row, mag_row, skip_row, x0, x1,
                                     up_right_last);
            } else {
              ok = z > 0 ? decodeRow(Flag<false>(), Flag<true>(), row, mag_row, skip_row, x0, x1,
                                     up_right_last)
                         : decodeRow(Flag<false>(), Flag<false>(), row, mag_row, skip_row, x0, x1,
                                     up_right_last);
            }
          }
      }
  std::free(nonzero);
  *rc = d;
  if (out.narrow_fits) *out.narrow_fits = all_magnitudes < (uint64_t{1} << 15);
  return ok;
}

}  // namespace

bool decodeUnpredictedArray(RangeDecoder* rc, const ArrayBox& box, const uint8_t* skip,
                            const ArrayDestination& out, uint16_t* magnitudes) {
  return out.narrow ? decodeArray<int16_t>(rc, box, skip, out, magnitudes)
                    : decodeArray<int64_t>(rc, box, skip, out, magnitudes);
}

}  // namespace mrsv
