// Arrays with weighted prediction (spec 5.7.5): exact round trips on real and
// extreme data, smaller than neighbour prediction on terrain, and garbage that
// decodes without overflow or values beyond the clamp.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bitstream/range_coder_adapter.h"
#include "grid/coefficient_coding.h"
#include "grid/weighted_array_coding.h"
#include "test_support.h"

namespace mrsv {
namespace {

std::vector<uint8_t> encode(std::vector<int64_t> values, const ArrayBox& box, ArrayPrediction p) {
  std::vector<uint8_t> bytes;
  RangeEncoder rc(&bytes);
  EncodingCoder coder{&rc};
  std::vector<int64_t> symbols(box.count());
  if (p == ArrayPrediction::kWeighted)
    EXPECT_TRUE(codeWeightedArray(coder, values.data(), symbols.data(), box));
  else
    EXPECT_TRUE(codeArray(coder, values.data(), symbols.data(), box, p, nullptr));
  rc.finish();
  return bytes;
}

void roundTrip(const std::vector<int64_t>& values, const ArrayBox& box) {
  std::vector<uint8_t> bytes = encode(values, box, ArrayPrediction::kWeighted);
  RangeDecoder rc(bytes.data(), bytes.size());
  DecodingCoder coder{&rc};
  std::vector<int64_t> back(box.count()), symbols(box.count());
  EXPECT_TRUE(codeWeightedArray(coder, back.data(), symbols.data(), box));
  EXPECT_EQ(back, values);
  EXPECT_EQ(rc.overrun(), 0u);
  EXPECT_EQ(rc.consumed(), bytes.size());
}

TEST(WeightedArrayCoding, TerrainIsLosslessAndSmallerThanNeighbourPrediction) {
  std::vector<uint8_t> raw = test::readFileOrFail(test::sourcePath("demo/data/mt_st_helens_128x128_int16le.raw"));
  ASSERT_EQ(raw.size(), 128u * 128 * 2);
  std::vector<int64_t> v(128 * 128);
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<int16_t>(raw[2 * i] | raw[2 * i + 1] << 8);
  ArrayBox box;
  box.num_dims = 2;
  box.size[0] = box.size[1] = 128;
  roundTrip(v, box);
  EXPECT_LT(encode(v, box, ArrayPrediction::kWeighted).size(),
            encode(v, box, ArrayPrediction::kNeighbour).size());
}

TEST(WeightedArrayCoding, SparseAndExtremeValuesEveryShape) {
  std::mt19937_64 rng(13);
  for (int dims = 1; dims <= 3; ++dims)
    for (int trial = 0; trial < 30; ++trial) {
      ArrayBox box;
      box.num_dims = dims;
      for (int a = 0; a < dims; ++a) box.size[a] = 1 + static_cast<uint32_t>(rng() % (dims == 1 ? 300 : dims == 2 ? 40 : 13));
      std::vector<int64_t> v(box.count(), 0);
      for (size_t i = 0; i < v.size(); ++i) {
        uint64_t r = rng();
        if (r % 3 == 0) v[i] = static_cast<int64_t>(rng() % 2001) - 1000;
        if (r % 53 == 0) v[i] = (r & 1 ? 1 : -1) * static_cast<int64_t>(rng() % (uint64_t{1} << 35));
      }
      roundTrip(v, box);
    }
}

TEST(WeightedArrayCoding, GarbageStaysWithinTheClamp) {
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 60; ++trial) {
    ArrayBox box;
    box.num_dims = 1 + trial % 3;
    for (int a = 0; a < box.num_dims; ++a) box.size[a] = 1 + static_cast<uint32_t>(rng() % 24);
    std::vector<uint8_t> garbage(1 + rng() % 4000);
    for (uint8_t& b : garbage) b = static_cast<uint8_t>(rng());
    // Mostly 1 bits drive magnitudes (and so values and errors) to the extremes.
    if (trial % 2) for (uint8_t& b : garbage) b |= 0xEF;
    garbage[0] = 0;
    RangeDecoder rc(garbage.data(), garbage.size());
    DecodingCoder coder{&rc};
    std::vector<int64_t> values(box.count()), symbols(box.count());
    codeWeightedArray(coder, values.data(), symbols.data(), box);
    for (int64_t v : values) ASSERT_LE(magnitudeOf(v), static_cast<uint64_t>(kArrayValueLimit));
  }
}

}  // namespace
}  // namespace mrsv
