// Rate-distortion optimised quantisation (informative 5.9): on a real
// terrain's high-pass, its choice costs less distortion plus lambda times the
// bits the range coder really spends than rounding or the dead zone does.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "bitstream/range_coder_adapter.h"
#include "grid/rd_quantizer.h"
#include "test_support.h"

namespace mrsv {
namespace {

constexpr int64_t kNoLimit = int64_t{1} << 35;

size_t codedBits(std::vector<int64_t> q, const ArrayBox& box) {
  std::vector<uint8_t> bytes;
  RangeEncoder rc(&bytes);
  EncodingCoder coder{&rc};
  std::vector<int64_t> symbols(box.count());
  EXPECT_TRUE(codeArray(coder, q.data(), symbols.data(), box, ArrayPrediction::kNone, nullptr));
  rc.finish();
  return 8 * bytes.size();
}

double distortion(const std::vector<double>& c, const std::vector<int64_t>& q) {
  double d = 0;
  for (size_t i = 0; i < c.size(); ++i) d += (c[i] - static_cast<double>(q[i])) * (c[i] - static_cast<double>(q[i]));
  return d;
}

std::vector<int64_t> deadZone(const std::vector<double>& c, double rounding) {
  std::vector<int64_t> q(c.size());
  for (size_t i = 0; i < c.size(); ++i) {
    const int64_t m = static_cast<int64_t>(std::floor(std::fabs(c[i]) + rounding));
    q[i] = c[i] < 0 ? -m : m;
  }
  return q;
}

// Second differences along x of the St Helens crop, in units of a step of 6.1
// m: a real detail band, mostly small with edges along the ridges.
std::vector<double> terrainHighPass(ArrayBox* box) {
  std::vector<uint8_t> raw = test::readFileOrFail(test::sourcePath("demo/data/mt_st_helens_128x128_int16le.raw"));
  EXPECT_EQ(raw.size(), 128u * 128 * 2);
  auto at = [&](size_t x, size_t y) {
    const size_t i = 2 * (x + 128 * y);
    return static_cast<double>(static_cast<int16_t>(raw[i] | raw[i + 1] << 8));
  };
  box->num_dims = 2;
  box->size[0] = 126;
  box->size[1] = 128;
  std::vector<double> c;
  for (size_t y = 0; y < 128; ++y)
    for (size_t x = 1; x < 127; ++x) c.push_back((at(x - 1, y) - 2 * at(x, y) + at(x + 1, y)) / 6.1);
  return c;
}

TEST(RdQuantizer, LambdaZeroRoundsToNearest) {
  ArrayBox box;
  std::vector<double> c = terrainHighPass(&box);
  std::vector<int64_t> q(c.size());
  rdQuantizeArray(c.data(), box, 0.0, kNoLimit, q.data());
  EXPECT_EQ(q, deadZone(c, 0.5));
}

TEST(RdQuantizer, BeatsRoundingAndDeadZoneOnRealTerrain) {
  ArrayBox box;
  std::vector<double> c = terrainHighPass(&box);
  const double lambda = 0.09;
  std::vector<int64_t> q(c.size());
  ASSERT_TRUE(rdQuantizeArray(c.data(), box, lambda, kNoLimit, q.data()));
  for (size_t i = 0; i < c.size(); ++i) {  // never above the nearest integer, never the wrong sign
    ASSERT_LE(std::abs(q[i]), std::llround(std::fabs(c[i])));
    ASSERT_TRUE(q[i] == 0 || (q[i] < 0) == (c[i] < 0));
  }
  const double j = distortion(c, q) + lambda * static_cast<double>(codedBits(q, box));
  for (double rounding : {0.5, 0.4, 0.3}) {
    std::vector<int64_t> plain = deadZone(c, rounding);
    const double j_plain = distortion(c, plain) + lambda * static_cast<double>(codedBits(plain, box));
    EXPECT_LT(j, j_plain) << "rounding " << rounding;
  }
  // A larger lambda trades distortion for bits.
  std::vector<int64_t> coarse(c.size());
  rdQuantizeArray(c.data(), box, 4 * lambda, kNoLimit, coarse.data());
  EXPECT_LT(codedBits(coarse, box), codedBits(q, box));
  EXPECT_GT(distortion(c, coarse), distortion(c, q));
}

TEST(RdQuantizer, QuietBlocksAreZeroedAndLimitsHold) {
  // 3-D: Laplacian values in one corner block, a lone 0.8 elsewhere, one huge value.
  ArrayBox box;
  box.num_dims = 3;
  box.size[0] = box.size[1] = box.size[2] = 12;
  std::vector<double> c(box.count(), 0.0);
  std::mt19937_64 rng(5);
  std::exponential_distribution<double> laplace(0.7);
  for (uint32_t z = 0; z < 4; ++z)
    for (uint32_t y = 0; y < 4; ++y)
      for (uint32_t x = 0; x < 4; ++x) c[x + 12 * (y + 12 * z)] = (rng() & 1 ? 1 : -1) * laplace(rng);
  c[6 + 12 * (6 + 12 * 6)] = 0.8;
  c[11 + 12 * (11 + 12 * 11)] = -1e12;
  std::vector<int64_t> q(c.size());
  ASSERT_TRUE(rdQuantizeArray(c.data(), box, 0.09, 1000, q.data()));
  EXPECT_EQ(q[6 + 12 * (6 + 12 * 6)], 0);  // alone, it costs more bits than it saves
  EXPECT_EQ(q[11 + 12 * (11 + 12 * 11)], -1000);
  int64_t corner = 0;
  for (uint32_t i = 0; i < 4; ++i) corner += std::abs(q[i]);
  EXPECT_GT(corner, 0);
}

}  // namespace
}  // namespace mrsv
