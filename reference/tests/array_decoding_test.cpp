// decodeUnpredictedArray() against codeArray(), the walk the encoder shares:
// on encoded arrays and on random bytes, the same values, the same verdict and
// the same bytes read, written into a strided destination and nowhere else.
// Both coders are header-only, so this runs in the decoder-only build too.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "bitstream/range_coder_adapter.h"
#include "grid/array_decoding.h"
#include "grid/coefficient_coding.h"

namespace mrsv {
namespace {

constexpr int64_t kUntouched = 0x5A5A5A5A5A5A5A5;

struct Reference {
  bool ok;
  std::vector<int64_t> values;
  size_t consumed, overrun;
};

Reference decodeWithCodeArray(const std::vector<uint8_t>& bytes, const ArrayBox& box,
                              const uint8_t* skip) {
  RangeDecoder rc(bytes.data(), bytes.size());
  DecodingCoder coder{&rc};
  std::vector<int64_t> values(box.count(), 0);
  const bool ok = codeArray(coder, values.data(), values.data(), box, ArrayPrediction::kNone, skip);
  return {ok, values, rc.consumed(), rc.overrun()};
}

// Decodes into the middle of a larger array (`pad` extra values per row and
// rows per slice, and a slice before and after), with dequantisation by `step`
// (0: none), and checks that the padding is untouched and that everything
// matches codeArray() followed by dequantizeSymbol().
void expectSameAsCodeArray(const std::vector<uint8_t>& bytes, const ArrayBox& box,
                           const uint8_t* skip, uint32_t pad, uint64_t step = 0) {
  Reference ref = decodeWithCodeArray(bytes, box, skip);
  if (step != 0)
    for (int64_t& v : ref.values) v = dequantizeSymbol(v, step);
  const size_t rs = box.size[0] + pad, ss = rs * (box.size[1] + pad);
  std::vector<int64_t> memory(ss * (box.size[2] + 2), kUntouched);
  const ArrayDestination out{memory.data() + ss, rs, ss, step};
  std::vector<uint16_t> magnitudes(box.count(), 0xABCD);  // its contents on entry unused
  RangeDecoder rc(bytes.data(), bytes.size());
  const bool ok = decodeUnpredictedArray(&rc, box, skip, out, magnitudes.data());
  ASSERT_EQ(ok, ref.ok);
  if (!ok) return;  // the decoder stopped at the same place, with an error
  EXPECT_EQ(rc.consumed(), ref.consumed);
  EXPECT_EQ(rc.overrun(), ref.overrun);
  for (size_t i = 0; i < memory.size(); ++i) {
    const size_t j = i - ss;  // position in the destination, if any
    const uint32_t x = static_cast<uint32_t>(j % rs), y = static_cast<uint32_t>(j / rs % (box.size[1] + pad));
    const uint32_t z = static_cast<uint32_t>(j / ss);
    const bool inside = i >= ss && z < box.size[2] && y < box.size[1] && x < box.size[0];
    if (!inside) {
      ASSERT_EQ(memory[i], kUntouched) << "written outside the box at " << i;
      continue;
    }
    ASSERT_EQ(memory[i], ref.values[x + box.size[0] * (y + size_t{box.size[1]} * z)])
        << "at " << x << "," << y << "," << z;
  }
}

std::vector<uint8_t> encode(const std::vector<int64_t>& values, const ArrayBox& box,
                            const uint8_t* skip) {
  std::vector<uint8_t> bytes;
  RangeEncoder rc(&bytes);
  EncodingCoder coder{&rc};
  std::vector<int64_t> copy = values, symbols(box.count());
  EXPECT_TRUE(codeArray(coder, copy.data(), symbols.data(), box, ArrayPrediction::kNone, skip));
  rc.finish();
  return bytes;
}

ArrayBox randomBox(std::mt19937_64& rng, int dims) {
  ArrayBox box;
  box.num_dims = dims;
  for (int a = 0; a < dims; ++a)
    box.size[a] = 1 + static_cast<uint32_t>(rng() % (dims == 1 ? 300 : dims == 2 ? 40 : 14));
  return box;
}

TEST(ArrayDecoding, EncodedArraysEveryShape) {
  std::mt19937_64 rng(5);
  for (int dims = 1; dims <= 3; ++dims)
    for (int trial = 0; trial < 40; ++trial) {
      const ArrayBox box = randomBox(rng, dims);
      std::vector<int64_t> v(box.count(), 0);
      std::vector<uint8_t> skip(box.count(), 0);
      const int density = 1 + static_cast<int>(rng() % 6);  // sparse to dense
      for (size_t i = 0; i < v.size(); ++i) {
        const uint64_t r = rng();
        if (r % density == 0) v[i] = static_cast<int64_t>(rng() % 9) - 4;
        if (r % 89 == 0) v[i] = (r & 1 ? 1 : -1) * static_cast<int64_t>(rng() % (uint64_t{1} << 39));
        if (r % 13 == 0) skip[i] = 1;
      }
      expectSameAsCodeArray(encode(v, box, nullptr), box, nullptr, trial % 3);
      // Dequantised in place: exact, and saturated for the large values.
      expectSameAsCodeArray(encode(v, box, nullptr), box, nullptr, 1, 1 + rng() % 5000);
      for (size_t i = 0; i < v.size(); ++i)
        if (skip[i]) v[i] = 0;
      expectSameAsCodeArray(encode(v, box, skip.data()), box, skip.data(), 1);
    }
}

// spec 5.7.3 step 5: a stream whose first symbol escapes with 39 prefix ones
// is in error, for both decoders alike. Random bytes almost never reach the
// escape (its interval starts at 5 / 32768), so this stream is written by hand
// with the models the decoder will use.
TEST(ArrayDecoding, TooLongEscapePrefixIsAnError) {
  ArrayBox box;
  box.num_dims = 2;
  box.size[0] = box.size[1] = 8;
  std::vector<uint8_t> bytes;
  RangeEncoder rc(&bytes);
  ArrayContexts ctx;
  rc.bit(&ctx.block[0], 1);  // the only block is coded
  rc.bit(&ctx.zero[0], 1);   // position (0, 0), class 0: nonzero
  rc.bit(&ctx.sign[0], 0);
  rc.symbol(&ctx.level[0], kSymbolCount - 1);  // the escape
  for (int j = 0; j < kMaxMagnitudeBits - 1; ++j) rc.bit(&ctx.magnitude[0][std::min(j, kMagnitudeModels - 1)], 1);
  rc.finish();
  expectSameAsCodeArray(bytes, box, nullptr, 1);
  EXPECT_FALSE(decodeWithCodeArray(bytes, box, nullptr).ok);
}

TEST(ArrayDecoding, RandomBytesDecodeAlike) {
  std::mt19937_64 rng(17);
  for (int dims = 1; dims <= 3; ++dims)
    for (int trial = 0; trial < 150; ++trial) {
      const ArrayBox box = randomBox(rng, dims);
      std::vector<uint8_t> bytes(rng() % 600);
      for (uint8_t& b : bytes) b = static_cast<uint8_t>(rng());
      // Skewed bytes give other paths (long runs of likely symbols).
      if (trial % 4 == 0)
        for (uint8_t& b : bytes) b |= 0xF0;
      std::vector<uint8_t> skip(box.count());
      for (uint8_t& s : skip) s = rng() % 7 == 0;
      expectSameAsCodeArray(bytes, box, trial % 2 ? skip.data() : nullptr, trial % 2,
                            trial % 3 == 0 ? 0 : rng() % 100000 + 1);
    }
}

}  // namespace
}  // namespace mrsv
