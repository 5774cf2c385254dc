// The CDF 9/7 fixed-point synthesis (spec 4.11.3) as the decoder runs it: the
// vectorised kernels against the scalar reference kernels on random values up
// to and beyond the saturation bound, and the whole synthesis (line layout,
// mirrored ends, batching, either set of kernels) against a line-by-line
// transcription of the pseudo-code of 4.11.3. Fixed seeds throughout.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "test_support.h"
#include "wavelet/axis_plan.h"
#include "wavelet/cdf97.h"
#include "wavelet/cdf97_kernels.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv::wavelet {
namespace {

// Random values of the kinds the kernels meet: small ones, ones near and at
// +-kValueLimit (where sat acts), and, where `any` is set, arbitrary int64
// (the scaling and the reading of the high half accept any input).
int64_t randomValue(std::mt19937_64& rng, bool any) {
  const uint64_t r = rng();
  switch (r % 6) {
    case 0: return static_cast<int64_t>(rng() % 2001) - 1000;
    case 1: return static_cast<int64_t>(rng() % (uint64_t{1} << 36)) - (int64_t{1} << 35);
    case 2: return kValueLimit - static_cast<int64_t>(rng() % 64);
    case 3: return -kValueLimit + static_cast<int64_t>(rng() % 64);
    case 4: return (r & 64) ? kValueLimit : -kValueLimit;
    default:
      if (any) return static_cast<int64_t>(rng());
      return static_cast<int64_t>(rng() % (2 * static_cast<uint64_t>(kValueLimit) + 1)) - kValueLimit;
  }
}

std::vector<int64_t> randomValues(std::mt19937_64& rng, size_t n, bool any) {
  std::vector<int64_t> v(n);
  for (int64_t& x : v) x = randomValue(rng, any);
  return v;
}

// The kernels to compare with the scalar ones: those the decoder uses here and
// every vectorised set this CPU runs.
std::vector<const Cdf97Kernels*> fastKernels() {
  std::vector<const Cdf97Kernels*> list = {&cdf97Kernels()};
  for (const Cdf97Kernels* k : {cdf97Avx2Kernels(), cdf97Avx512Kernels()})
    if (k && k != list[0]) list.push_back(k);
  return list;
}

TEST(Cdf97Kernels, ScaleAndSaturateMatchTheScalarKernels) {
  const Cdf97Kernels& ref = cdf97ScalarKernels();
  std::mt19937_64 rng(97);
  for (const Cdf97Kernels* k : fastKernels()) {
    for (size_t n = 0; n < 40; ++n) {
      for (size_t offset = 0; offset < 3; ++offset) {  // unaligned starts too
        // Random values; all 0; all 0 but one (the kernels tell whether an output is not 0).
        std::vector<int64_t> x = randomValues(rng, n + offset, true);
        for (int kind = 0; kind < 3; ++kind) {
          if (kind > 0) std::fill(x.begin(), x.end(), 0);
          if (kind == 2 && n > 0) x[offset + rng() % n] = (rng() & 1) ? 1 : -1;
          std::vector<int64_t> want(n + offset, 7), got(n + offset, 7);
          bool want_any = ref.scale(x.data() + offset, want.data() + offset, n);
          bool got_any = k->scale(x.data() + offset, got.data() + offset, n);
          ASSERT_EQ(got, want) << k->name << " scale n=" << n;
          ASSERT_EQ(got_any, want_any) << k->name << " scale n=" << n;
          ASSERT_EQ(want_any, kind != 1 && n > 0);
          want_any = ref.saturate(x.data() + offset, want.data() + offset, n);
          got_any = k->saturate(x.data() + offset, got.data() + offset, n);
          ASSERT_EQ(got, want) << k->name << " saturate n=" << n;
          ASSERT_EQ(got_any, want_any) << k->name << " saturate n=" << n;
        }
      }
    }
    // The ends of the int64 range and of the saturation bound, each in every lane.
    const std::vector<int64_t> edges = {INT64_MIN,      INT64_MIN + 1,  -kValueLimit - 1,
                                        -kValueLimit,   -kValueLimit + 1, -1,
                                        0,              1,              kValueLimit - 1,
                                        kValueLimit,    kValueLimit + 1, INT64_MAX};
    std::vector<int64_t> want(edges.size()), got(edges.size());
    ref.scale(edges.data(), want.data(), edges.size());
    k->scale(edges.data(), got.data(), edges.size());
    EXPECT_EQ(got, want) << k->name;
    ref.saturate(edges.data(), want.data(), edges.size());
    k->saturate(edges.data(), got.data(), edges.size());
    EXPECT_EQ(got, want) << k->name;
  }
}

TEST(Cdf97Kernels, LiftMatchesTheScalarKernel) {
  const Cdf97Kernels& ref = cdf97ScalarKernels();
  std::mt19937_64 rng(4113);
  // The coefficients of 4.11.2 and others within the kernels' precondition.
  std::vector<int64_t> coefficients = {kCdf97Alpha, kCdf97Beta, kCdf97Gamma, kCdf97Delta,
                                       kCdf97K,     0,          1,           -1,
                                       (int64_t{1} << 26) - 1, -(int64_t{1} << 26) + 1};
  for (int i = 0; i < 20; ++i)
    coefficients.push_back(static_cast<int64_t>(rng() % (uint64_t{1} << 27)) - (int64_t{1} << 26));
  for (const Cdf97Kernels* k : fastKernels()) {
    for (int64_t c : coefficients) {
      for (size_t n : {size_t{0}, size_t{1}, size_t{3}, size_t{4}, size_t{5}, size_t{17}, size_t{300}}) {
        const std::vector<int64_t> a = randomValues(rng, n + 1, false);
        const std::vector<int64_t> b = randomValues(rng, n + 1, false);
        const std::vector<int64_t> y = randomValues(rng, n + 1, false);
        std::vector<int64_t> want = y, got = y;
        ref.lift(want.data() + 1, a.data(), b.data() + 1, n, c);
        k->lift(got.data() + 1, a.data(), b.data() + 1, n, c);
        ASSERT_EQ(got, want) << k->name << " c=" << c << " n=" << n;
      }
    }
    // Sums at +-2 kValueLimit: the largest products of 4.11.4.
    const size_t n = 64;
    for (int64_t c : {kCdf97Alpha, kCdf97K, -kCdf97Alpha}) {
      for (int64_t edge : {kValueLimit, -kValueLimit}) {
        std::vector<int64_t> a(n, edge), b(n, edge), y = randomValues(rng, n, false);
        std::vector<int64_t> want = y, got = y;
        ref.lift(want.data(), a.data(), b.data(), n, c);
        k->lift(got.data(), a.data(), b.data(), n, c);
        ASSERT_EQ(got, want) << k->name << " c=" << c << " edge=" << edge;
      }
    }
  }
}

TEST(Cdf97Kernels, InterleaveMatchesTheScalarKernel) {
  const Cdf97Kernels& ref = cdf97ScalarKernels();
  std::mt19937_64 rng(5);
  for (const Cdf97Kernels* k : fastKernels()) {
    for (size_t f = 2; f < 40; ++f) {
      const size_t h = (f + 1) / 2, g = f - h;
      const std::vector<int64_t> even = randomValues(rng, h, true), odd = randomValues(rng, g, true);
      std::vector<int64_t> want(f + 1, 3), got(f + 1, 3);  // the entry past the end stays
      ref.interleave(even.data(), odd.data(), want.data(), h, g);
      k->interleave(even.data(), odd.data(), got.data(), h, g);
      ASSERT_EQ(got, want) << k->name << " f=" << f;
    }
  }
}

// spec: 4.11.3, transcribed line by line (natural order, mirrored indices).
void synthesizeAsWritten(const GridPlan& plan, int64_t* data, int stop_level) {
  auto sat = [](int64_t v) { return v > kValueLimit ? kValueLimit : v < -kValueLimit ? -kValueLimit : v; };
  auto shift = [](int64_t t) { return t >= 0 ? t >> 24 : ~(~t >> 24); };  // floor(t / 2^24)
  const size_t stride[3] = {1, plan.axis[0].size(0), size_t{plan.axis[0].size(0)} * plan.axis[1].size(0)};
  for (int j = plan.maxLevels(); j > stop_level; --j) {
    for (int a = 0; a < 3; ++a) {
      if (plan.axis[a].levels < j) continue;
      const size_t f = plan.axis[a].size(j - 1), h = plan.axis[a].size(j);
      size_t box[3];
      for (int b = 0; b < 3; ++b) box[b] = plan.axis[b].size(j - 1);
      box[a] = 1;
      std::vector<int64_t> x(f);
      for (size_t z = 0; z < box[2]; ++z)
        for (size_t y = 0; y < box[1]; ++y)
          for (size_t xx = 0; xx < box[0]; ++xx) {
            int64_t* line = data + xx + y * stride[1] + z * stride[2];
            auto value = [&](size_t i) -> int64_t& { return line[i * stride[a]]; };
            for (size_t i = 0; i < h; ++i) x[2 * i] = sat(shift(sat(value(i)) * kCdf97K + (1 << 23)));
            for (size_t i = 0; i + h < f; ++i) x[2 * i + 1] = sat(value(h + i));
            auto step = [&](size_t p, int64_t c) {
              for (size_t i = p; i < f; i += 2) {
                const size_t l = i > 0 ? i - 1 : i + 1, r = i + 1 < f ? i + 1 : i - 1;
                x[i] = sat(x[i] - shift(c * (x[l] + x[r]) + (1 << 23)));
              }
            };
            step(0, kCdf97Delta);
            step(1, kCdf97Gamma);
            step(0, kCdf97Beta);
            step(1, kCdf97Alpha);
            for (size_t i = 0; i < f; ++i) value(i) = x[i];
          }
    }
  }
}

using test::cdf97Plan;

TEST(Cdf97Kernels, SynthesisMatchesSpecWithEveryKernelSet) {
  // Odd and even lengths, 2 and 3 values on a split level, unequal depths,
  // boxes narrower and wider than a batch of lines.
  const std::vector<GridPlan> plans = {
      cdf97Plan(1, 2, 1, 1, 1, 0, 0),      cdf97Plan(1, 3, 1, 1, 2, 0, 0),
      cdf97Plan(1, 1201, 1, 1, 7, 0, 0),   cdf97Plan(2, 37, 23, 1, 3, 2, 0),
      cdf97Plan(2, 317, 61, 1, 5, 4, 0),   cdf97Plan(3, 9, 10, 11, 2, 3, 1),
      cdf97Plan(3, 16, 5, 33, 4, 0, 5),    cdf97Plan(3, 70, 3, 41, 1, 1, 3),
      cdf97Plan(3, 5, 300, 7, 0, 6, 2)};
  std::vector<const Cdf97Kernels*> kernels = fastKernels();
  kernels.push_back(&cdf97ScalarKernels());
  std::mt19937_64 rng(2024);
  for (const GridPlan& plan : plans) {
    // Coefficient-like values (mostly small), with some at and beyond the bound.
    // About half the values 0, in runs, so that some lines and batches are all 0.
    std::vector<int64_t> input(plan.paddedCount());
    bool zeros = false;
    for (int64_t& v : input) {
      if (rng() % 64 == 0) zeros = !zeros;
      const uint64_t r = rng() % 16;
      v = zeros ? 0
          : r < 12 ? static_cast<int64_t>(rng() % (uint64_t{1} << 28)) - (int64_t{1} << 27)
                   : randomValue(rng, true);
    }
    for (int stop = 0; stop <= 2; ++stop) {
      std::vector<int64_t> want = input;
      synthesizeAsWritten(plan, want.data(), stop);
      for (const Cdf97Kernels* k : kernels) {
        std::vector<int64_t> got = input;
        synthesizeFixedCdf97(plan, got.data(), stop, *k);
        ASSERT_EQ(got, want) << k->name << " " << plan.axis[0].samples << "x"
                             << plan.axis[1].samples << "x" << plan.axis[2].samples << " stop "
                             << stop;
      }
      std::vector<int64_t> got = input;
      synthesizeFixed(plan, got.data(), stop);  // the decoder's entry point
      ASSERT_EQ(got, want);
    }
  }
}

TEST(Cdf97Kernels, LastPassRowsAreTheSynthesis) {
  // The rows handed out by the last pass are the values the synthesis would
  // have written, each position once; when the last pass is along x nothing
  // is handed out and the array holds the result.
  const std::vector<GridPlan> plans = {
      cdf97Plan(1, 1201, 1, 1, 7, 0, 0),  // last pass along x
      cdf97Plan(2, 317, 61, 1, 5, 4, 0),  // along y
      cdf97Plan(2, 37, 23, 1, 3, 0, 0),   // along x (y not transformed)
      cdf97Plan(3, 9, 10, 11, 2, 3, 1),   // along z
      cdf97Plan(3, 70, 3, 41, 1, 1, 0),   // along y (z not transformed)
      cdf97Plan(3, 300, 20, 7, 6, 2, 2)}; // along z, boxes wider than a batch
  std::mt19937_64 rng(58);
  for (const GridPlan& plan : plans) {
    std::vector<int64_t> input(plan.paddedCount());
    for (int64_t& v : input) v = static_cast<int64_t>(rng() % (uint64_t{1} << 30)) - (int64_t{1} << 29);
    for (int stop = 0; stop <= 1; ++stop) {
      std::vector<int64_t> want = input;
      synthesizeAsWritten(plan, want.data(), stop);
      struct Collected {
        std::vector<int64_t> values;
        std::vector<int> seen;
        size_t px, pxy;
      } got{std::vector<int64_t>(input.size()), std::vector<int>(input.size()),
            plan.axis[0].size(0), size_t{plan.axis[0].size(0)} * plan.axis[1].size(0)};
      const SynthesisRows rows{
          [](void* c, size_t x, size_t y, size_t z, const int64_t* values, size_t n) {
            Collected& got = *static_cast<Collected*>(c);
            for (size_t i = 0; i < n; ++i) {
              const size_t at = x + i + y * got.px + z * got.pxy;
              got.values[at] = values[i];
              ++got.seen[at];
            }
          },
          &got};
      for (const Cdf97Kernels* k : {&cdf97ScalarKernels(), &cdf97Kernels()}) {
        std::vector<int64_t> data = input;
        std::fill(got.seen.begin(), got.seen.end(), 0);
        const bool handed_out = synthesizeFixedCdf97(plan, data.data(), stop, rows, *k);
        const bool along_x_last = plan.axis[1].levels <= stop && plan.axis[2].levels <= stop;
        ASSERT_EQ(handed_out, !along_x_last && plan.maxLevels() > stop);
        size_t box[3];
        for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(std::min(stop, plan.axis[a].levels));
        for (size_t z = 0; z < box[2]; ++z)
          for (size_t y = 0; y < box[1]; ++y)
            for (size_t x = 0; x < box[0]; ++x) {
              const size_t at = x + y * got.px + z * got.pxy;
              if (handed_out) {
                ASSERT_EQ(got.seen[at], 1) << x << "," << y << "," << z;
                ASSERT_EQ(got.values[at], want[at]) << k->name;
              } else {
                ASSERT_EQ(data[at], want[at]) << k->name;
              }
            }
      }
    }
  }
}

TEST(Cdf97Kernels, LastLevelFromRowsIsTheSynthesis) {
  // The last level synthesised slice by slice from rows of the Mallat layout
  // hands out every position once, with the values of the whole synthesis;
  // plans it cannot take are refused. Odd and even depths (the mirrored ends
  // of the pass along z), 2 and 3 slices, unequal depths, values near the bound.
  const std::vector<GridPlan> plans = {
      cdf97Plan(3, 9, 10, 11, 2, 3, 1),  cdf97Plan(3, 16, 5, 33, 4, 1, 5),
      cdf97Plan(3, 70, 3, 2, 1, 1, 1),   cdf97Plan(3, 7, 6, 3, 1, 2, 1),
      cdf97Plan(3, 300, 20, 8, 6, 2, 2), cdf97Plan(3, 33, 17, 12, 3, 3, 3)};
  std::mt19937_64 rng(77);
  for (const GridPlan& plan : plans) {
    std::vector<int64_t> input(plan.paddedCount());
    bool zeros = false;
    for (int64_t& v : input) {
      if (rng() % 64 == 0) zeros = !zeros;
      v = zeros ? 0
          : rng() % 8 ? static_cast<int64_t>(rng() % (uint64_t{1} << 30)) - (int64_t{1} << 29)
                      : randomValue(rng, true);
    }
    std::vector<int64_t> want = input;
    synthesizeAsWritten(plan, want.data(), 0);
    std::vector<int64_t> level1 = input;  // every level above 1 synthesised
    synthesizeFixedCdf97(plan, level1.data(), 1);
    struct State {
      const std::vector<int64_t>* level1;
      std::vector<int64_t> values;
      std::vector<int> seen;
      size_t px, pxy;
    } st{&level1, std::vector<int64_t>(input.size()), std::vector<int>(input.size()),
         plan.axis[0].size(0), size_t{plan.axis[0].size(0)} * plan.axis[1].size(0)};
    const MallatRows from{[](void* c, size_t y, size_t z, int64_t* values) {
                            const State& st = *static_cast<const State*>(c);
                            const int64_t* row = st.level1->data() + y * st.px + z * st.pxy;
                            std::copy(row, row + st.px, values);
                          },
                          &st};
    const SynthesisRows to{[](void* c, size_t x, size_t y, size_t z, const int64_t* values,
                              size_t n) {
                             State& st = *static_cast<State*>(c);
                             for (size_t i = 0; i < n; ++i) {
                               st.values[x + i + y * st.px + z * st.pxy] = values[i];
                               ++st.seen[x + i + y * st.px + z * st.pxy];
                             }
                           },
                           &st};
    for (const Cdf97Kernels* k : {&cdf97ScalarKernels(), &cdf97Kernels()}) {
      std::fill(st.seen.begin(), st.seen.end(), 0);
      ASSERT_TRUE(synthesizeLastLevelCdf97(plan, from, to, *k));
      ASSERT_EQ(st.seen, std::vector<int>(input.size(), 1));
      ASSERT_EQ(st.values, want) << k->name << " " << plan.axis[0].samples << "x"
                                 << plan.axis[1].samples << "x" << plan.axis[2].samples;
    }
  }
  // Not split along every axis at level 1: refused, nothing called.
  for (const GridPlan& plan : {cdf97Plan(3, 9, 10, 11, 2, 0, 1), cdf97Plan(2, 37, 23, 1, 3, 2, 0)}) {
    const MallatRows from{[](void*, size_t, size_t, int64_t*) { FAIL(); }, nullptr};
    const SynthesisRows to{[](void*, size_t, size_t, size_t, const int64_t*, size_t) { FAIL(); },
                           nullptr};
    EXPECT_FALSE(synthesizeLastLevelCdf97(plan, from, to));
  }
}

TEST(Cdf97Kernels, AvailableImplementations) {
  // Documents what this machine runs; the comparisons above cover it.
  const Cdf97Kernels& best = cdf97Kernels();
  if (cdf97Avx512Kernels()) EXPECT_STREQ(best.name, "avx512");
  else if (cdf97Avx2Kernels()) EXPECT_STREQ(best.name, "avx2");
  else EXPECT_STREQ(best.name, "scalar");
  RecordProperty("cdf97_kernels", best.name);
}

}  // namespace
}  // namespace mrsv::wavelet
