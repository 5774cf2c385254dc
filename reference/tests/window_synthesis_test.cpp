// The windowed synthesis of one axis step (wavelet/window_synthesis.h) against
// the whole grid's synthesis: every window of outputs of every level, for every
// wavelet, from random coefficients (some beyond the saturation bound) and from
// inputs restricted to what inputs() names.
#include <gtest/gtest.h>

#include <random>

#include "wavelet/cdf97.h"
#include "wavelet/synthesis_fixed.h"
#include "wavelet/window_synthesis.h"

namespace mrsv::wavelet {
namespace {

// One level of a 1-D grid synthesised whole: the outputs of level j from the
// array synthesised down to level j (the same call the decoder makes).
std::vector<int64_t> wholeLevel(const GridPlan& plan, std::vector<int64_t> data, int j) {
  if (isCdf97(plan.axis[0].order))
    synthesizeFixedCdf97(plan, data.data(), j - 1, j);
  else
    synthesizeFixed(plan, data.data(), j - 1, j);
  data.resize(plan.axis[0].size(j - 1));
  return data;
}

TEST(WindowSynthesis, EveryWindowEqualsTheWholeLine) {
  std::mt19937_64 rng(20261127);
  int checked = 0;
  for (int order : {1, 2, 3, 4, kOrderCdf97})
    for (uint32_t n : {7u, 16u, 33u, 100u, 257u}) {
      const int levels = 3;
      const uint32_t samples[3] = {n, 1, 1};
      const int lv[3] = {levels, 0, 0};
      GridPlan plan;
      if (!makeGridPlan(1, samples, order, lv, &plan)) continue;
      ++checked;
      std::vector<int64_t> data(plan.paddedCount());
      for (int64_t& v : data) {
        const uint64_t r = rng();
        v = r % 50 == 0 ? static_cast<int64_t>(r) : static_cast<int64_t>(r % 200001) - 100000;
      }
      for (int j = 1; j <= levels; ++j) {
        const std::vector<int64_t> whole = wholeLevel(plan, data, j);
        const WindowLine w(plan.axis[0], j);
        ASSERT_EQ(w.fine(), whole.size());
        std::vector<int64_t> scratch, out;
        for (int trial = 0; trial < 40; ++trial) {
          uint32_t a = static_cast<uint32_t>(rng() % w.fine()), b = static_cast<uint32_t>(rng() % w.fine());
          if (a > b) std::swap(a, b);
          ++b;
          // Only the named inputs: every other value of the line is garbage.
          const WindowInputs in = w.inputs(a, b);
          std::vector<int64_t> line(w.fine(), int64_t{1} << 40);
          for (uint32_t i = in.low0; i < in.low1; ++i) line[i] = data[i];
          for (uint32_t i = in.high0; i < in.high1; ++i) line[w.low() + i] = data[w.low() + i];
          out.assign(b - a, 0);
          w.synthesize(in, line.data() + in.low0, line.data() + w.low() + in.high0, a, b, out.data(), &scratch);
          for (uint32_t i = a; i < b; ++i)
            ASSERT_EQ(out[i - a], whole[i]) << "order " << order << " n " << n << " level " << j
                                            << " window " << a << ".." << b << " at " << i;
        }
      }
    }
  EXPECT_GE(checked, 15);  // every wavelet with most lengths
}

}  // namespace
}  // namespace mrsv::wavelet
