// The array coder of spec 5.7 on real data: what is coded decodes exactly.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "bitstream/range_coder_adapter.h"
#include "grid/coefficient_coding.h"
#include "test_support.h"

namespace mrsv {
namespace {

std::vector<uint8_t> encode(std::vector<int64_t> values, const ArrayBox& box, ArrayPrediction p,
                            const uint8_t* skip) {
  std::vector<uint8_t> bytes;
  RangeEncoder rc(&bytes);
  EncodingCoder coder{&rc};
  std::vector<int64_t> symbols(box.count());
  EXPECT_TRUE(codeArray(coder, values.data(), symbols.data(), box, p, skip));
  rc.finish();
  return bytes;
}

std::vector<int64_t> decode(const ArrayBox& box, ArrayPrediction p, const uint8_t* skip,
                            RangeDecoder* rc) {
  DecodingCoder coder{rc};
  std::vector<int64_t> values(box.count()), symbols(box.count());
  EXPECT_TRUE(codeArray(coder, values.data(), symbols.data(), box, p, skip));
  return values;
}

void roundTrip(const std::vector<int64_t>& values, const ArrayBox& box, ArrayPrediction p,
               const uint8_t* skip = nullptr) {
  std::vector<uint8_t> bytes = encode(values, box, p, skip);
  RangeDecoder rc(bytes.data(), bytes.size());
  std::vector<int64_t> back = decode(box, p, skip, &rc);
  EXPECT_EQ(back, values);
  EXPECT_EQ(rc.overrun(), 0u);
  EXPECT_EQ(rc.consumed(), bytes.size());
}

TEST(CoefficientCoding, RealTerrainWithPredictionIsLosslessAndCompact) {
  std::vector<uint8_t> raw = test::readFileOrFail(test::sourcePath("demo/data/mt_st_helens_128x128_int16le.raw"));
  ASSERT_EQ(raw.size(), 128u * 128 * 2);
  std::vector<int64_t> v(128 * 128);
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<int16_t>(raw[2 * i] | raw[2 * i + 1] << 8);
  ArrayBox box;
  box.num_dims = 2;
  box.size[0] = box.size[1] = 128;
  roundTrip(v, box, ArrayPrediction::kNeighbour);
  // Smooth terrain predicts well: far below the 16 bits per sample of the raw file.
  EXPECT_LT(encode(v, box, ArrayPrediction::kNeighbour, nullptr).size(), raw.size() / 3);
}

TEST(CoefficientCoding, SparseAndExtremeValuesEveryShape) {
  std::mt19937_64 rng(7);
  for (int dims = 1; dims <= 3; ++dims) {
    for (int trial = 0; trial < 20; ++trial) {
      ArrayBox box;
      box.num_dims = dims;
      for (int a = 0; a < dims; ++a) box.size[a] = 1 + static_cast<uint32_t>(rng() % (dims == 1 ? 300 : dims == 2 ? 40 : 13));
      std::vector<int64_t> v(box.count(), 0);
      std::vector<uint8_t> skip(box.count(), 0);
      for (size_t i = 0; i < v.size(); ++i) {
        uint64_t r = rng();
        if (r % 5 == 0) v[i] = static_cast<int64_t>(rng() % 7) - 3;
        if (r % 97 == 0) v[i] = (r & 1 ? 1 : -1) * static_cast<int64_t>(rng() % (uint64_t{1} << 35));
        if (r % 11 == 0) skip[i] = 1;
      }
      roundTrip(v, box, ArrayPrediction::kNone);
      roundTrip(v, box, ArrayPrediction::kNeighbour);
      std::vector<int64_t> masked = v;
      for (size_t i = 0; i < v.size(); ++i)
        if (skip[i]) masked[i] = 0;
      roundTrip(masked, box, ArrayPrediction::kNone, skip.data());
      roundTrip(masked, box, ArrayPrediction::kNeighbour, skip.data());
    }
  }
}

// spec 5.7.3: the last magnitudes of the 16-ary symbol (14, 15), the first
// escapes (16, 17) and the largest codable one, 2^39 + 14; 2^39 + 15 would need
// a 40th prefix bit, which the encoder refuses.
TEST(CoefficientCoding, MagnitudesAroundTheEscapeAndTheLimit) {
  ArrayBox box;
  box.num_dims = 1;
  box.size[0] = 12;
  const int64_t largest = (int64_t{1} << 39) + 14;
  roundTrip({14, -15, 16, -17, 0, 15, 1, -16, largest, -largest, 17, 0}, box, ArrayPrediction::kNone);
  std::vector<uint8_t> bytes;
  RangeEncoder rc(&bytes);
  EncodingCoder coder{&rc};
  std::vector<int64_t> values(12, 0), symbols(12);
  values[3] = largest + 1;
  EXPECT_FALSE(codeArray(coder, values.data(), symbols.data(), box, ArrayPrediction::kNone, nullptr));
}

TEST(CoefficientCoding, GarbageNeverOverflows) {
  std::mt19937_64 rng(11);
  ArrayBox box;
  box.num_dims = 3;
  box.size[0] = box.size[1] = box.size[2] = 20;
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<uint8_t> garbage(1 + rng() % 4000);
    for (uint8_t& b : garbage) b = static_cast<uint8_t>(rng());
    garbage[0] = 0;
    RangeDecoder rc(garbage.data(), garbage.size());
    DecodingCoder coder{&rc};
    std::vector<int64_t> values(box.count()), symbols(box.count());
    codeArray(coder, values.data(), symbols.data(), box, ArrayPrediction::kNeighbour, nullptr);
    for (int64_t v : values) ASSERT_LE(magnitudeOf(v), static_cast<uint64_t>(kArrayValueLimit));
  }
}

}  // namespace
}  // namespace mrsv
