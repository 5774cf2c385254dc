// Axis plans, grid plans, the band layout and the filter tables (spec 4.2-4.4).
// Decode side: no Eigen, no floating-point transform.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "wavelet/axis_plan.h"
#include "wavelet/filter_tables.h"
#include "wavelet/level_filters.h"

namespace mrsv::wavelet {
namespace {

TEST(WaveletPlan, MinCoarseIntervals) {
  EXPECT_EQ(minCoarseIntervals(1), 1);
  EXPECT_EQ(minCoarseIntervals(2), 4);
  EXPECT_EQ(minCoarseIntervals(3), 7);
  EXPECT_EQ(minCoarseIntervals(4), 11);
  EXPECT_EQ(minCoarseIntervals(0), 0);
  EXPECT_EQ(minCoarseIntervals(5), 0);
}

TEST(WaveletPlan, AxisPlanSizes) {
  AxisPlan p;
  ASSERT_TRUE(makeAxisPlan(1201, 4, 3, &p));
  // n_0 = ceil((1201 - 3) / 8) = 150; size(j) = 150 * 2^(3-j) + 3.
  EXPECT_EQ(p.coarse_intervals, 150u);
  EXPECT_EQ(p.size(0), 1203u);
  EXPECT_EQ(p.size(1), 603u);
  EXPECT_EQ(p.size(2), 303u);
  EXPECT_EQ(p.size(3), 153u);
  EXPECT_EQ(p.size(7), 153u);  // not split beyond its levels
  EXPECT_EQ(p.intervals(1), 600u);

  ASSERT_TRUE(makeAxisPlan(17, 3, 0, &p));
  EXPECT_EQ(p.size(0), 17u);
  EXPECT_EQ(p.size(2), 17u);
  EXPECT_EQ(p.coarse_intervals, 0u);
  ASSERT_TRUE(makeAxisPlan(1, 4, 0, &p));  // fewer samples than the order: untransformed is fine
  EXPECT_EQ(p.size(0), 1u);
}

TEST(WaveletPlan, ImpossiblePlansAreRefused) {
  AxisPlan p;
  EXPECT_FALSE(makeAxisPlan(3, 4, 1, &p));               // N < k
  EXPECT_FALSE(makeAxisPlan(0, 1, 0, &p));               // no samples
  EXPECT_FALSE(makeAxisPlan(100, 0, 0, &p));             // order
  EXPECT_FALSE(makeAxisPlan(100, 6, 1, &p));             // order (5 is CDF 9/7)
  EXPECT_FALSE(makeAxisPlan(100, 2, -1, &p));            // levels
  EXPECT_FALSE(makeAxisPlan(1u << 24, 1, kMaxLevels + 1, &p));
  EXPECT_TRUE(makeAxisPlan(1u << 24, 1, kMaxLevels, &p));
  // n_0 = ceil((24 - 3) / 2) = 11 = n_min(4), but 21/4 -> 6 < 11.
  EXPECT_TRUE(makeAxisPlan(24, 4, 1, &p));
  EXPECT_FALSE(makeAxisPlan(24, 4, 2, &p));
  // The padded length must fit 32 bits.
  EXPECT_FALSE(makeAxisPlan(UINT32_MAX, 1, 16, &p));
  EXPECT_TRUE(makeAxisPlan(UINT32_MAX - 65535, 1, 16, &p));
}

TEST(WaveletPlan, PaddingIsBelowTwoToTheLevels) {
  for (int k = kMinOrder; k <= kMaxOrder; ++k)
    for (uint32_t n = 1; n <= 700; ++n)
      for (int levels = 1; levels <= 8; ++levels) {
        AxisPlan p;
        if (!makeAxisPlan(n, k, levels, &p)) continue;
        EXPECT_GE(p.size(0), n);
        EXPECT_LT(p.size(0) - n, 1u << levels) << n << " " << k << " " << levels;
        EXPECT_GE(p.coarse_intervals, static_cast<uint32_t>(minCoarseIntervals(k)));
        for (int j = 0; j <= levels; ++j)
          EXPECT_EQ(p.size(j), (p.coarse_intervals << (levels - j)) + k - 1);
      }
}

TEST(WaveletPlan, ChooseLevelsPadsAtMostOneThirtySecond) {
  int transformed = 0;
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    for (uint32_t n = 2; n <= 5000; ++n) {
      const int levels = chooseLevels(n, k, kMaxLevels);
      ASSERT_GE(levels, 0);
      for (int more = levels + 1; more <= kMaxLevels; ++more) {
        AxisPlan q;  // no deeper plan qualifies
        if (makeAxisPlan(n, k, more, &q)) {
          EXPECT_GT((q.size(0) - n) * 32, n) << n;
        }
      }
      if (levels == 0) continue;
      ++transformed;
      AxisPlan p;
      ASSERT_TRUE(makeAxisPlan(n, k, levels, &p)) << n << " " << k;
      EXPECT_LE(p.size(0) - n, n / 32) << "N " << n << " order " << k;
    }
  }
  EXPECT_GT(transformed, 4 * 4000);
  EXPECT_EQ(chooseLevels(1201, 4, 2), 2);  // max_levels is respected
  EXPECT_EQ(chooseLevels(1201, 4, 0), 0);
  EXPECT_EQ(chooseLevels(3, 4, 16), 0);
}

TEST(WaveletPlan, StructuralValidity) {
  GridPlan plan;
  const uint32_t n[3] = {100, 60, 1};
  const int levels[3] = {2, 1, 0};
  ASSERT_TRUE(makeGridPlan(2, n, 4, levels, &plan));
  EXPECT_TRUE(isValidGridPlan(plan));
  GridPlan bad = plan;
  bad.axis[0].coarse_intervals = 10;  // below n_min(4) = 11
  EXPECT_FALSE(isValidGridPlan(bad));
  bad = plan;
  bad.axis[1].order = 6;  // neither a B-spline order nor 9/7 (5)
  EXPECT_FALSE(isValidGridPlan(bad));
  bad = plan;
  bad.axis[0].levels = kMaxLevels + 1;
  EXPECT_FALSE(isValidGridPlan(bad));
  bad = plan;
  bad.axis[0].coarse_intervals = 1u << 20;
  bad.axis[0].levels = 12;  // padded length beyond 2^32
  EXPECT_FALSE(isValidGridPlan(bad));
  bad = plan;
  bad.num_dims = 4;
  EXPECT_FALSE(isValidGridPlan(bad));
}

// Counts how often each padded position is covered by a band.
void expectBandsTile(const GridPlan& plan) {
  const std::vector<Band> bands = bandsOf(plan);
  const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0),
                 nz = plan.axis[2].size(0);
  std::vector<uint8_t> hits(plan.paddedCount(), 0);
  ASSERT_FALSE(bands.empty());
  EXPECT_EQ(bands[0].mask, 0);
  EXPECT_EQ(bands[0].level, plan.maxLevels());
  for (size_t b = 0; b < bands.size(); ++b) {
    const Band& band = bands[b];
    if (b > 0) {
      EXPECT_NE(band.mask, 0);
      const Band& prev = bands[b - 1];
      if (b > 1) {
        EXPECT_TRUE(band.level < prev.level || band.mask > prev.mask);
      }
      for (int a = 0; a < 3; ++a) {
        if (band.mask & (1 << a)) {
          EXPECT_GE(plan.axis[a].levels, band.level);
        }
      }
    }
    for (uint32_t z = 0; z < band.size[2]; ++z)
      for (uint32_t y = 0; y < band.size[1]; ++y)
        for (uint32_t x = 0; x < band.size[0]; ++x) {
          const uint64_t at = (uint64_t{band.offset[2] + z} * ny + band.offset[1] + y) * nx +
                              band.offset[0] + x;
          ASSERT_LT(band.offset[0] + x, nx);
          ASSERT_LT(band.offset[1] + y, ny);
          ASSERT_LT(band.offset[2] + z, nz);
          ++hits[at];
        }
  }
  for (size_t i = 0; i < hits.size(); ++i) ASSERT_EQ(hits[i], 1) << "position " << i;
}

TEST(WaveletPlan, BandsCoverThePaddedArrayOnce) {
  struct Case {
    int dims;
    uint32_t n[3];
    int order;
    int levels[3];
  };
  const Case cases[] = {
      {1, {1201, 1, 1}, 4, {6, 0, 0}},   {1, {1201, 1, 1}, 1, {10, 0, 0}},
      {1, {5, 1, 1}, 2, {0, 0, 0}},      {2, {317, 460, 1}, 2, {5, 3, 0}},
      {2, {317, 460, 1}, 4, {4, 5, 0}},  {2, {40, 9, 1}, 3, {2, 0, 0}},
      {3, {64, 64, 93}, 3, {3, 3, 3}},   {3, {64, 64, 93}, 4, {2, 1, 3}},
      {3, {33, 17, 70}, 1, {5, 4, 0}},   {3, {12, 30, 50}, 2, {1, 2, 3}},
  };
  for (const Case& c : cases) {
    GridPlan plan;
    ASSERT_TRUE(makeGridPlan(c.dims, c.n, c.order, c.levels, &plan));
    expectBandsTile(plan);
  }
}

TEST(WaveletPlan, BandOrderAndSizes) {
  GridPlan plan;
  const uint32_t n[3] = {317, 460, 1};
  const int levels[3] = {2, 1, 0};
  ASSERT_TRUE(makeGridPlan(2, n, 2, levels, &plan));
  // x: n_0 = ceil(316/4) = 79, sizes 317, 159, 80; y: n_0 = ceil(459/2) = 230, sizes 461, 231.
  const std::vector<Band> bands = bandsOf(plan);
  ASSERT_EQ(bands.size(), 5u);
  EXPECT_EQ(bands[0].level, 2);
  EXPECT_EQ(bands[0].size[0], 80u);
  EXPECT_EQ(bands[0].size[1], 231u);  // y is not split at level 2
  EXPECT_EQ(bands[1].level, 2);
  EXPECT_EQ(bands[1].mask, 1);
  EXPECT_EQ(bands[1].offset[0], 80u);
  EXPECT_EQ(bands[1].size[0], 79u);
  EXPECT_EQ(bands[1].size[1], 231u);
  EXPECT_EQ(bands[2].level, 1);
  EXPECT_EQ(bands[2].mask, 1);
  EXPECT_EQ(bands[3].mask, 2);
  EXPECT_EQ(bands[3].offset[1], 231u);
  EXPECT_EQ(bands[3].size[1], 230u);
  EXPECT_EQ(bands[3].size[0], 159u);
  EXPECT_EQ(bands[4].mask, 3);

  GridPlan none;
  const int zero[3] = {0, 0, 0};
  ASSERT_TRUE(makeGridPlan(2, n, 2, zero, &none));
  ASSERT_EQ(bandsOf(none).size(), 1u);
  EXPECT_EQ(bandsOf(none)[0].level, 0);
  EXPECT_EQ(none.paddedCount(), 317u * 460u);
}

// Every fine row of [P|Q] is reached only within the level, the integer P rows sum
// to exactly 2^24 (constants are reproduced exactly by the decoder), and the
// largest sum of |integer taps| over a row is the one spec 4.6 relies on.
TEST(WaveletFilters, LevelColumnsAreConsistent) {
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    const OrderFilters& f = orderFilters(k);
    int64_t worst = 0;
    for (uint32_t n = static_cast<uint32_t>(minCoarseIntervals(k)); n < 60; ++n) {
      const LevelFilters lf(k, n);
      ASSERT_EQ(lf.fine(), lf.coarse() + lf.wavelets());
      std::vector<int64_t> p_sum(lf.fine(), 0), abs_sum(lf.fine(), 0);
      for (uint32_t j = 0; j < lf.coarse(); ++j) {
        const Column c = lf.p(j);
        ASSERT_LE(c.first_row + c.count, lf.fine());
        for (int r = 0; r < c.count; ++r) {
          p_sum[c.first_row + r] += c.fixed[r];
          abs_sum[c.first_row + r] += c.fixed[r] < 0 ? -int64_t{c.fixed[r]} : c.fixed[r];
        }
      }
      for (uint32_t j = 0; j < lf.wavelets(); ++j) {
        const Column c = lf.q(j);
        ASSERT_LE(c.first_row + c.count, lf.fine());
        if (j > 0) {
          EXPECT_GE(c.first_row, lf.q(j - 1).first_row);
        }
        for (int r = 0; r < c.count; ++r)
          abs_sum[c.first_row + r] += c.fixed[r] < 0 ? -int64_t{c.fixed[r]} : c.fixed[r];
      }
      for (uint32_t i = 0; i < lf.fine(); ++i) {
        EXPECT_EQ(p_sum[i], int64_t{1} << kTapFracBits) << "order " << k << " n " << n;
        worst = std::max(worst, abs_sum[i]);
      }
    }
    EXPECT_EQ(worst, f.max_row_tap_sum) << "order " << k;
    EXPECT_LE(worst, kMaxRowTapSum);
  }
}

}  // namespace
}  // namespace mrsv::wavelet
