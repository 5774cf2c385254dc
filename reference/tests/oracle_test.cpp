// The oracles of the encoder (paper 2.2): exact L2 errors through the Gram
// matrices, the global keep oracle and the support-aware local oracle.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "grid/oracle.h"
#include "mrsv/encode.h"
#include "mrsv/grid.h"
#include "shared_data.h"
#include "wavelet/transform_float.h"

namespace mrsv {
namespace {

// The exact norm, computed band by band in the semi-orthogonal basis, equals
// the norm of the synthesised function computed with the finest Gram matrix:
// two different routes to the same number, which holds only if the bands are
// mutually orthogonal and the band Gram matrices are right.
TEST(Oracle, BandwiseL2NormEqualsNormOfSynthesisedFunction) {
  for (int order = 1; order <= 4; ++order) {
    wavelet::GridPlan plan;
    const uint32_t samples[3] = {70, 53, 1};
    const int levels[3] = {2, 2, 0};
    ASSERT_TRUE(wavelet::makeGridPlan(2, samples, order, levels, &plan)) << order;
    std::vector<wavelet::Band> bands = wavelet::bandsOf(plan);
    std::mt19937_64 rng(order);
    std::normal_distribution<double> normal;
    std::vector<double> e(plan.paddedCount());
    for (double& v : e) v = normal(rng);
    double bandwise = functionSpaceNormSquared(plan, bands, e);

    std::vector<double> f = e;
    wavelet::synthesize(plan, f.data());
    const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0);
    // f^T (G_x (x) G_y) f with the Gram matrices of the finest B-splines.
    double direct = 0;
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x)
        for (uint32_t y2 = y >= 8 ? y - 8 : 0; y2 < std::min(ny, y + 9); ++y2)
          for (uint32_t x2 = x >= 8 ? x - 8 : 0; x2 < std::min(nx, x + 9); ++x2) {
            double g = wavelet::gramEntry(order, plan.axis[0].intervals(0), x, x2) *
                       wavelet::gramEntry(order, plan.axis[1].intervals(0), y, y2);
            direct += f[x + nx * y] * g * f[x2 + nx * y2];
          }
    EXPECT_NEAR(bandwise, direct, 1e-9 * direct) << "order " << order;
  }
}

struct Terrain {
  GridHeader header;
  std::vector<uint8_t> samples;
  double at(size_t i) const {
    int16_t v;
    std::memcpy(&v, &samples[2 * i], 2);
    return v;
  }
};

Terrain helens() {
  test::SharedGrid g;
  EXPECT_TRUE(test::loadSharedGrid(std::string(MRSV_SHARED_DATA) +
                                       "/terrain/mt_st_helens_317x460_int16le.raw.zst", &g));
  return {g.header, g.samples};
}

TEST(Oracle, KeepFractionKeepsThatManyAndMoreIsBetter) {
  Terrain t = helens();
  double previous_l2 = 1e300;
  for (double fraction : {0.01, 0.05, 0.2}) {
    WaveletEncodeOptions options;
    options.keep_fraction = fraction;
    std::vector<uint8_t> stream;
    WaveletEncodeReport report;
    ASSERT_TRUE(encodeWaveletGrid(t.header, t.samples, Metadata{}, options, &stream, &report).ok());
    double padded = 0;  // kept counts coefficients of the padded array
    {
      wavelet::GridPlan plan;
      const uint32_t s[3] = {t.header.size_x, t.header.size_y, 1};
      const int lv[3] = {wavelet::chooseLevels(s[0], 4, 16), wavelet::chooseLevels(s[1], 4, 16), 0};
      ASSERT_TRUE(wavelet::makeGridPlan(2, s, 4, lv, &plan));
      padded = static_cast<double>(plan.paddedCount());
    }
    EXPECT_LE(static_cast<double>(report.kept_coefficients), std::ceil(fraction * padded)) << fraction;
    EXPECT_GE(static_cast<double>(report.kept_coefficients), 0.9 * fraction * padded) << fraction;
    EXPECT_LT(report.l2_error, previous_l2) << fraction;
    EXPECT_GT(report.l2_error, 0);
    previous_l2 = report.l2_error;
  }
}

TEST(Oracle, RegionOfInterestKeepsDetailWhereItIsAsked) {
  Terrain t = helens();
  WaveletEncodeOptions options;
  options.bits_per_sample = 0.5;
  options.has_roi = true;
  options.roi.center[0] = 160;
  options.roi.center[1] = 230;
  options.roi.half_size[0] = options.roi.half_size[1] = 40;
  options.roi.falloff = 8;
  std::vector<uint8_t> stream;
  WaveletEncodeReport report;
  ASSERT_TRUE(encodeWaveletGrid(t.header, t.samples, Metadata{}, options, &stream, &report).ok());
  DecodedGrid out;
  ASSERT_TRUE(decodeGrid(stream.data(), stream.size(), DecodeOptions{}, &out).ok());
  double in_sse = 0, out_sse = 0;
  size_t in_n = 0, out_n = 0;
  for (uint32_t y = 0; y < t.header.size_y; ++y)
    for (uint32_t x = 0; x < t.header.size_x; ++x) {
      size_t i = x + size_t{t.header.size_x} * y;
      int16_t v;
      std::memcpy(&v, &out.samples[2 * i], 2);
      double d = v - t.at(i);
      bool inside = std::fabs(x - 160.0) <= 40 && std::fabs(y - 230.0) <= 40;
      (inside ? in_sse : out_sse) += d * d;
      (inside ? in_n : out_n) += 1;
    }
  double in_mse = in_sse / static_cast<double>(in_n), out_mse = out_sse / static_cast<double>(out_n);
  // Inside: at least 10 dB better than outside at the same overall rate.
  EXPECT_LT(in_mse * 10, out_mse) << "inside " << in_mse << " outside " << out_mse;

  // Without the region, the same rate spreads its error evenly.
  WaveletEncodeOptions plain;
  plain.bits_per_sample = 0.5;
  ASSERT_TRUE(encodeWaveletGrid(t.header, t.samples, Metadata{}, plain, &stream, &report).ok());
  ASSERT_TRUE(decodeGrid(stream.data(), stream.size(), DecodeOptions{}, &out).ok());
  double plain_in = 0;
  for (uint32_t y = 190; y <= 270; ++y)
    for (uint32_t x = 120; x <= 200; ++x) {
      size_t i = x + size_t{t.header.size_x} * y;
      int16_t v;
      std::memcpy(&v, &out.samples[2 * i], 2);
      plain_in += (v - t.at(i)) * (v - t.at(i));
    }
  EXPECT_LT(in_mse, plain_in / static_cast<double>(in_n) / 4) << "the region is much better than without it";
}

}  // namespace
}  // namespace mrsv
