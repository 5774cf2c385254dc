// The baseline entropy mode (spec 5.10): exact round trips, and damaged
// payloads rejected with a reason, never crashing.
#include <gtest/gtest.h>

#include <random>

#include "grid/baseline_coding.h"
#include "test_support.h"

namespace mrsv {
namespace {

void roundTrip(const std::vector<int64_t>& values, const ArrayBox& box, ArrayPrediction p,
               const uint8_t* skip = nullptr) {
  std::vector<uint8_t> bytes;
  encodeBaselineArray(values.data(), box, p, skip, &bytes);
  std::vector<int64_t> back(box.count(), 7);
  std::string problem = decodeBaselineArray(bytes.data(), bytes.size(), box, p, skip, back.data());
  ASSERT_EQ(problem, "");
  EXPECT_EQ(back, values);
}

TEST(BaselineCoding, RealTerrainAndEveryShape) {
  std::vector<uint8_t> raw = test::readFileOrFail(test::sourcePath("demo/data/mt_st_helens_128x128_int16le.raw"));
  std::vector<int64_t> v(128 * 128);
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<int16_t>(raw[2 * i] | raw[2 * i + 1] << 8);
  ArrayBox box;
  box.num_dims = 2;
  box.size[0] = box.size[1] = 128;
  roundTrip(v, box, ArrayPrediction::kNeighbour);
  roundTrip(v, box, ArrayPrediction::kNone);

  std::mt19937_64 rng(3);
  for (int dims = 1; dims <= 3; ++dims)
    for (int trial = 0; trial < 20; ++trial) {
      ArrayBox b;
      b.num_dims = dims;
      for (int a = 0; a < dims; ++a) b.size[a] = 1 + static_cast<uint32_t>(rng() % (dims == 3 ? 12 : 70));
      std::vector<int64_t> x(b.count(), 0);
      std::vector<uint8_t> skip(b.count(), 0);
      for (size_t i = 0; i < x.size(); ++i) {
        uint64_t r = rng();
        if (r % 4 == 0) x[i] = static_cast<int64_t>(rng() % 9) - 4;
        if (r % 89 == 0) x[i] = (r & 1 ? 1 : -1) * static_cast<int64_t>(rng() % (uint64_t{1} << 38));
        if (r % 13 == 0) {
          skip[i] = 1;
          x[i] = 0;
        }
      }
      roundTrip(x, b, ArrayPrediction::kNone);
      roundTrip(x, b, ArrayPrediction::kNone, skip.data());
      roundTrip(x, b, ArrayPrediction::kNeighbour, skip.data());
    }
  std::vector<int64_t> zeros(1000, 0);
  ArrayBox line;
  line.size[0] = 1000;
  roundTrip(zeros, line, ArrayPrediction::kNone);
}

TEST(BaselineCoding, DamageIsReported) {
  std::vector<int64_t> v(300);
  for (size_t i = 0; i < v.size(); ++i) v[i] = static_cast<int64_t>(i % 7) - 3;
  ArrayBox box;
  box.size[0] = 300;
  std::vector<uint8_t> bytes;
  encodeBaselineArray(v.data(), box, ArrayPrediction::kNone, nullptr, &bytes);
  std::vector<int64_t> out(300);
  std::vector<uint8_t> cut(bytes.begin(), bytes.end() - 1);
  EXPECT_NE(decodeBaselineArray(cut.data(), cut.size(), box, ArrayPrediction::kNone, nullptr, out.data()), "");
  std::vector<uint8_t> extra = bytes;
  extra.push_back(0);
  EXPECT_NE(decodeBaselineArray(extra.data(), extra.size(), box, ArrayPrediction::kNone, nullptr, out.data()), "");
  std::mt19937_64 rng(5);
  for (int trial = 0; trial < 2000; ++trial) {
    std::vector<uint8_t> garbage = bytes;
    garbage[rng() % garbage.size()] ^= static_cast<uint8_t>(1u << (rng() % 8));
    decodeBaselineArray(garbage.data(), garbage.size(), box, ArrayPrediction::kNeighbour, nullptr, out.data());
    for (int64_t x : out) ASSERT_LE(magnitudeOf(x), static_cast<uint64_t>(kArrayValueLimit));
  }
}

}  // namespace
}  // namespace mrsv
