// The CDF 9/7 wavelet (spec 4.11): plans and sizes, the real transform's
// perfect reconstruction, the fixed-point synthesis against it, a hand-checked
// level, and inputs at the saturation bound.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "test_support.h"
#include "wavelet/axis_plan.h"
#include "wavelet/cdf97.h"
#include "wavelet/synthesis_fixed.h"
#include "wavelet/transform_float.h"

namespace mrsv::wavelet {
namespace {

using test::cdf97Plan;

// Odd and even lengths, unequal depths, down to 2 values on a split level.
std::vector<GridPlan> somePlans() {
  return {cdf97Plan(1, 2, 1, 1, 1, 0, 0),        cdf97Plan(1, 3, 1, 1, 2, 0, 0),
          cdf97Plan(1, 1201, 1, 1, 7, 0, 0),     cdf97Plan(2, 37, 23, 1, 3, 2, 0),
          cdf97Plan(2, 317, 460, 1, 5, 6, 0),    cdf97Plan(3, 9, 10, 11, 2, 3, 1),
          cdf97Plan(3, 16, 5, 33, 4, 0, 5)};
}

std::vector<double> smoothWithNoise(uint64_t count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, 3.0);
  std::vector<double> v(count);
  for (uint64_t i = 0; i < count; ++i) v[i] = 500 + 300 * std::sin(0.01 * static_cast<double>(i)) + noise(rng);
  return v;
}

TEST(Cdf97, SizesAndLevels) {
  AxisPlan a;
  ASSERT_TRUE(makeAxisPlan(1201, kOrderCdf97, 7, &a));
  EXPECT_EQ(a.size(0), 1201u);  // no padding
  EXPECT_EQ(a.size(1), 601u);
  EXPECT_EQ(a.size(7), 10u);    // ceil(1201 / 128)
  EXPECT_EQ(a.size(9), 10u);    // beyond the axis' levels: its coarsest size
  EXPECT_EQ(chooseLevels(1201, kOrderCdf97, kMaxLevels), 7);  // the coarsest level keeps >= 8
  EXPECT_EQ(chooseLevels(14, kOrderCdf97, kMaxLevels), 0);  // ceil(14 / 2) = 7
  EXPECT_EQ(chooseLevels(15, kOrderCdf97, kMaxLevels), 1);
  EXPECT_EQ(chooseLevels(29, kOrderCdf97, kMaxLevels), 2);  // ceil(29 / 4) = 8
  EXPECT_EQ(chooseLevels(1201, kOrderCdf97, 3), 3);
  // A split level needs 2 values: 3 samples allow 2 levels (3 -> 2 -> 1), not 3.
  EXPECT_TRUE(makeAxisPlan(3, kOrderCdf97, 2, &a));
  EXPECT_FALSE(makeAxisPlan(3, kOrderCdf97, 3, &a));
  EXPECT_FALSE(makeAxisPlan(1, kOrderCdf97, 1, &a));
  EXPECT_TRUE(makeAxisPlan(1, kOrderCdf97, 0, &a));
}

TEST(Cdf97, RealTransformReconstructsPerfectly) {
  for (const GridPlan& plan : somePlans()) {
    std::vector<double> x = smoothWithNoise(plan.paddedCount(), 7);
    std::vector<double> c = x;
    analyze(plan, c.data());
    synthesize(plan, c.data());
    double worst = 0;
    for (size_t i = 0; i < x.size(); ++i) worst = std::max(worst, std::fabs(c[i] - x[i]));
    EXPECT_LT(worst, 1e-9 * 800) << plan.axis[0].samples << "x" << plan.axis[1].samples;
  }
}

TEST(Cdf97, LowPassHasUnitGainAndDetailsVanishOnCubics) {
  // The analysis low-pass is normalised to gain 1 (4.11: the low values are in
  // sample units); the analysis high-pass has 4 vanishing moments, so a cubic
  // gives (away from the ends) zero detail coefficients.
  const GridPlan plan = cdf97Plan(1, 64, 1, 1, 1, 0, 0);
  std::vector<double> c(64, 5.0);
  analyze(plan, c.data());
  for (int i = 0; i < 32; ++i) EXPECT_NEAR(c[i], 5.0, 1e-6);
  for (int i = 0; i < 64; ++i) {
    double t = i / 64.0;
    c[i] = 3 * t * t * t - 2 * t * t + t;
  }
  analyze(plan, c.data());
  for (int i = 32 + 3; i < 64 - 3; ++i) EXPECT_NEAR(c[i], 0.0, 1e-6) << i;
}

TEST(Cdf97, FixedPointFollowsTheRealSynthesis) {
  for (const GridPlan& plan : somePlans()) {
    std::vector<double> real = smoothWithNoise(plan.paddedCount(), 11);
    analyze(plan, real.data());
    // Coefficients on a grid of 1/4, in fixed point with 16 fractional bits.
    std::vector<int64_t> fixed(real.size());
    for (size_t i = 0; i < real.size(); ++i) {
      real[i] = std::round(real[i] * 4) / 4;
      fixed[i] = static_cast<int64_t>(std::llround(real[i] * 65536));
    }
    synthesize(plan, real.data());
    synthesizeFixed(plan, fixed.data());
    double worst = 0;
    for (size_t i = 0; i < real.size(); ++i)
      worst = std::max(worst, std::fabs(static_cast<double>(fixed[i]) / 65536 - real[i]));
    EXPECT_LT(worst, 1e-3) << plan.axis[0].samples << "x" << plan.axis[1].samples;
  }
}

TEST(Cdf97, OneLevelByHand) {
  // Two values, one level: low s, high d. x0 = s*K, x1 = d; the steps of 4.11.3
  // with both neighbours of each value mirrored onto the other value.
  const GridPlan plan = cdf97Plan(1, 2, 1, 1, 1, 0, 0);
  auto step = [](int64_t c, int64_t v) {  // floor((c * v + 2^23) / 2^24)
    const int64_t t = c * v + (int64_t{1} << 23);
    return t >= 0 ? t >> 24 : ~(~t >> 24);
  };
  for (int64_t s : {int64_t{1000}, int64_t{-77777}}) {
    for (int64_t d : {int64_t{0}, int64_t{31}, int64_t{-4096}}) {
      int64_t x0 = step(kCdf97K, s), x1 = d;
      x0 -= step(kCdf97Delta, 2 * x1);
      x1 -= step(kCdf97Gamma, 2 * x0);
      x0 -= step(kCdf97Beta, 2 * x1);
      x1 -= step(kCdf97Alpha, 2 * x0);
      std::vector<int64_t> data = {s, d};
      synthesizeFixed(plan, data.data());
      EXPECT_EQ(data, (std::vector<int64_t>{x0, x1})) << s << " " << d;
    }
  }
}

TEST(Cdf97, ExtremeInputsSaturate) {
  // Any int64 input is read saturated and every output stays within the bound (4.11.4).
  const GridPlan plan = cdf97Plan(2, 37, 23, 1, 3, 2, 0);
  std::mt19937_64 rng(3);
  std::vector<int64_t> data(plan.paddedCount());
  for (int64_t& v : data) {
    uint64_t r = rng();
    v = (r & 1) ? INT64_MAX - static_cast<int64_t>(r >> 40) : INT64_MIN + static_cast<int64_t>(r >> 40);
  }
  synthesizeFixed(plan, data.data());
  for (int64_t v : data) EXPECT_LE(v < 0 ? -v : v, kValueLimit);
}

}  // namespace
}  // namespace mrsv::wavelet
