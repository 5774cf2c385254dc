// The normative fixed-point synthesis (spec 4.5, 4.6). Decode side: no Eigen,
// no floating-point transform; the agreement with the real transform is in
// wavelet_transform_test.cpp.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "wavelet/axis_plan.h"
#include "wavelet/level_filters.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv::wavelet {
namespace {

GridPlan planOf(int dims, uint32_t nx, uint32_t ny, uint32_t nz, int order, int lx, int ly,
                int lz) {
  const uint32_t n[3] = {nx, ny, nz};
  const int levels[3] = {lx, ly, lz};
  GridPlan plan;
  EXPECT_TRUE(makeGridPlan(dims, n, order, levels, &plan));
  return plan;
}

// Small plans of every order and dimension, some with axes of unequal depth.
std::vector<GridPlan> somePlans() {
  std::vector<GridPlan> plans;
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    const int n_min = minCoarseIntervals(k);
    const uint32_t d = static_cast<uint32_t>(k - 1);
    plans.push_back(planOf(1, 1201, 1, 1, k, chooseLevels(1201, k, kMaxLevels), 0, 0));
    plans.push_back(planOf(2, n_min * 4 + d, n_min * 2 + d + 1, 1, k, 2, 1, 0));
    plans.push_back(planOf(3, n_min * 2 + d, n_min * 4 + d - 1, n_min + d + 2, k, 1, 2, 0));
  }
  return plans;
}

TEST(WaveletFixed, HaarByHand) {
  // Haar, one level, 4 samples: c = (a+b), (a-b) per pair with taps 1 and -1 (exact).
  const GridPlan plan = planOf(1, 4, 1, 1, 1, 1, 0, 0);
  const int64_t one = int64_t{1} << 16;
  std::vector<int64_t> data = {10 * one, -3 * one, 2 * one, 5 * one};  // c0 c1 d0 d1
  synthesizeFixed(plan, data.data());
  EXPECT_EQ(data, (std::vector<int64_t>{12 * one, 8 * one, 2 * one, -8 * one}));
}

TEST(WaveletFixed, RoundingIsHalfUpWithAFlooringShift) {
  // Linear order, one level, n = 4: fine row 1 takes P tap 1/2 of c0 and c1.
  const GridPlan plan = planOf(1, 9, 1, 1, 2, 1, 0, 0);
  ASSERT_EQ(plan.axis[0].size(1), 5u);
  for (int64_t c : {int64_t{3}, int64_t{-3}, int64_t{1}, int64_t{-1}}) {
    std::vector<int64_t> data(9, 0);
    data[0] = c;  // row 1 = c/2 exactly before rounding: floor(c/2 + 1/2)
    synthesizeFixed(plan, data.data());
    const int64_t expected = c >= 0 ? (c + 1) / 2 : -((-c) / 2);
    EXPECT_EQ(data[1], expected) << c;
    EXPECT_EQ(data[0], c);
  }
}

TEST(WaveletFixed, ConstantsAreReproducedExactly) {
  // Every integer P row sums to 2^24, so a constant scaling block with zero details
  // synthesizes to the same constant everywhere (spec 4.5, note).
  for (const GridPlan& plan : somePlans()) {
    std::vector<int64_t> data(plan.paddedCount(), 0);
    const Band top = bandsOf(plan)[0];
    const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0);
    const int64_t value = -1234567;
    for (uint32_t z = 0; z < top.size[2]; ++z)
      for (uint32_t y = 0; y < top.size[1]; ++y)
        for (uint32_t x = 0; x < top.size[0]; ++x) data[(size_t{z} * ny + y) * nx + x] = value;
    synthesizeFixed(plan, data.data());
    for (size_t i = 0; i < data.size(); ++i) ASSERT_EQ(data[i], value) << i;
  }
}

// All values at +-kValueLimit in patterns that drive accumulators to their extremes;
// UBSan (MRSV_SANITIZE) reports any signed overflow. Values stay saturated.
TEST(WaveletFixed, AdversarialInputsDoNotOverflow) {
  std::mt19937_64 rng(20240611);
  for (const GridPlan& plan : somePlans()) {
    const size_t count = plan.paddedCount();
    for (int pattern = 0; pattern < 5; ++pattern) {
      std::vector<int64_t> data(count);
      for (size_t i = 0; i < count; ++i) {
        bool positive = true;
        switch (pattern) {
          case 0: positive = true; break;
          case 1: positive = false; break;
          case 2: positive = (i & 1) == 0; break;
          case 3: positive = (i / 3) % 2 == 0; break;
          default: positive = (rng() & 1) != 0; break;
        }
        data[i] = positive ? kValueLimit : -kValueLimit;
      }
      synthesizeFixed(plan, data.data());
      for (size_t i = 0; i < count; ++i) {
        ASSERT_LE(data[i], kValueLimit);
        ASSERT_GE(data[i], -kValueLimit);
      }
    }
    // Out-of-range input is saturated when read, never undefined.
    std::vector<int64_t> wild(count);
    for (size_t i = 0; i < count; ++i) wild[i] = (rng() & 1) ? INT64_MAX : INT64_MIN;
    synthesizeFixed(plan, wild.data());
    for (int64_t v : wild) ASSERT_LE(v < 0 ? -v : v, kValueLimit);
  }
}

// The row of largest sum |tap|, fed sign(tap) * kValueLimit, reaches the bound of
// spec 4.6 (computed here independently, in 128 bits) and saturates.
TEST(WaveletFixed, WorstRowReachesTheDocumentedBound) {
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    const uint32_t n = static_cast<uint32_t>(minCoarseIntervals(k)) + 3;
    const LevelFilters lf(k, n);
    std::vector<std::vector<std::pair<uint32_t, int32_t>>> rows(lf.fine());
    for (uint32_t j = 0; j < lf.coarse(); ++j) {
      const Column c = lf.p(j);
      for (int r = 0; r < c.count; ++r) rows[c.first_row + r].push_back({j, c.fixed[r]});
    }
    for (uint32_t j = 0; j < lf.wavelets(); ++j) {
      const Column c = lf.q(j);
      for (int r = 0; r < c.count; ++r)
        rows[c.first_row + r].push_back({lf.coarse() + j, c.fixed[r]});
    }
    uint32_t worst = 0;
    __int128 worst_sum = 0;
    for (uint32_t i = 0; i < lf.fine(); ++i) {
      __int128 s = 0;
      for (auto [col, tap] : rows[i]) s += tap < 0 ? -__int128{tap} : __int128{tap};
      if (s > worst_sum) worst_sum = s, worst = i;
    }
    EXPECT_EQ(static_cast<int64_t>(worst_sum), orderFilters(k).max_row_tap_sum);
    EXPECT_LT(worst_sum * kValueLimit + (1 << 23), static_cast<__int128>(INT64_MAX));

    const GridPlan plan = planOf(1, lf.fine(), 1, 1, k, 1, 0, 0);
    ASSERT_EQ(plan.axis[0].size(0), lf.fine());
    for (int sign : {1, -1}) {
      std::vector<int64_t> data(lf.fine(), 0);
      for (auto [col, tap] : rows[worst]) data[col] = (tap < 0 ? -sign : sign) * kValueLimit;
      synthesizeFixed(plan, data.data());
      EXPECT_EQ(data[worst], sign * kValueLimit) << "order " << k;
    }
  }
}

// Stopping at level s leaves exactly the Mallat layout of the same grid with s levels
// per axis at most; synthesizing that gives the full result.
TEST(WaveletFixed, PartialSynthesisComposes) {
  std::mt19937_64 rng(7);
  for (const GridPlan& plan : somePlans()) {
    const int top = plan.maxLevels();
    std::vector<int64_t> input(plan.paddedCount());
    for (int64_t& v : input) v = static_cast<int64_t>(rng() % 2000001) - 1000000;
    std::vector<int64_t> full = input;
    synthesizeFixed(plan, full.data());
    for (int stop = 1; stop < top; ++stop) {
      std::vector<int64_t> part = input;
      synthesizeFixed(plan, part.data(), stop);
      GridPlan rest = plan;
      for (AxisPlan& a : rest.axis) {
        if (a.levels > stop) {
          a.coarse_intervals = a.intervals(stop);
          a.levels = stop;
        }
      }
      synthesizeFixed(rest, part.data());
      ASSERT_EQ(part, full) << "stop " << stop;
    }
    std::vector<int64_t> none = input;
    synthesizeFixed(plan, none.data(), top);
    EXPECT_EQ(none, input);
  }
}

uint64_t fnv1a(const std::vector<int64_t>& v) {
  uint64_t h = 1469598103934665603ull;
  for (int64_t x : v)
    for (int b = 0; b < 8; ++b) {
      h ^= static_cast<uint64_t>(x >> (8 * b)) & 0xff;
      h *= 1099511628211ull;
    }
  return h;
}

// Golden outputs, computed independently from the text of spec 4.5 and the
// integer tables by `python3 tools/wavelets/make_filters.py --golden`. A change
// here changes what every decoder must produce.
TEST(WaveletFixed, GoldenOutputs) {
  const uint64_t expected[4] = {0x8ef2a061cb9fd654ull, 0xe0e292e40182b575ull,
                                0x35582e4eef1a6a85ull, 0x4ec09f7d0b87a884ull};
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    const GridPlan plan = planOf(3, 51, 29, 27, k, 2, 1, 1);
    std::vector<int64_t> data(plan.paddedCount());
    uint64_t s = 0x9E3779B97F4A7C15ull * k;
    for (int64_t& v : data) {  // splitmix64: the same numbers on every platform
      s += 0x9E3779B97F4A7C15ull;
      uint64_t z = s;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      z ^= z >> 31;
      v = static_cast<int64_t>(z % (uint64_t{1} << 30)) - (int64_t{1} << 29);
    }
    synthesizeFixed(plan, data.data());
    EXPECT_EQ(fnv1a(data), expected[k - 1]) << "order " << k << ": 0x" << std::hex
                                            << fnv1a(data);
  }
}

}  // namespace
}  // namespace mrsv::wavelet
