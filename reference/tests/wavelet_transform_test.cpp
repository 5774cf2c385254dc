// The floating-point transform of the encoder (spec 4.8, 4.9) and its agreement
// with the normative fixed-point synthesis (spec 4.7).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "test_support.h"
#include "wavelet/axis_plan.h"
#include "wavelet/level_filters.h"
#include "wavelet/synthesis_fixed.h"
#include "wavelet/transform_float.h"

namespace mrsv::wavelet {
namespace {

// --- data ---------------------------------------------------------------------

// The 128x128 terrain crop of Mount St. Helens (int16 little-endian).
const std::vector<double>& terrain() {
  static const std::vector<double> heights = [] {
    std::vector<uint8_t> bytes =
        test::readFileOrFail(test::sourcePath("demo/data/mt_st_helens_128x128_int16le.raw"));
    std::vector<double> h(bytes.size() / 2);
    for (size_t i = 0; i < h.size(); ++i)
      h[i] = static_cast<int16_t>(bytes[2 * i] | (bytes[2 * i + 1] << 8));
    return h;
  }();
  return heights;
}

// Bilinear sample of the terrain at (u, v) in [0, 1]^2.
double terrainAt(double u, double v) {
  const std::vector<double>& t = terrain();
  if (t.size() != 128 * 128) return 0.0;
  const double x = u * 127, y = v * 127;
  const int x0 = std::min(static_cast<int>(x), 126), y0 = std::min(static_cast<int>(y), 126);
  const double fx = x - x0, fy = y - y0;
  auto at = [&](int xx, int yy) { return t[static_cast<size_t>(yy) * 128 + xx]; };
  return (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x0 + 1, y0)) +
         fy * ((1 - fx) * at(x0, y0 + 1) + fx * at(x0 + 1, y0 + 1));
}

enum class Data { kTerrain, kRandom };

// Samples at positions < N of every axis; the padding repeats the last sample.
std::vector<double> makeData(const GridPlan& plan, Data kind, uint64_t seed) {
  const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0), nz = plan.axis[2].size(0);
  std::vector<double> out(plan.paddedCount());
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1000.0, 1000.0);
  for (uint32_t z = 0; z < nz; ++z)
    for (uint32_t y = 0; y < ny; ++y)
      for (uint32_t x = 0; x < nx; ++x) {
        const uint32_t sx = std::min(x, plan.axis[0].samples - 1);
        const uint32_t sy = std::min(y, plan.axis[1].samples - 1);
        const uint32_t sz = std::min(z, plan.axis[2].samples - 1);
        double v;
        if (kind == Data::kRandom) {
          v = uni(rng);
        } else {
          const double u = plan.axis[0].samples > 1 ? double(sx) / (plan.axis[0].samples - 1) : 0;
          const double w = plan.axis[1].samples > 1 ? double(sy) / (plan.axis[1].samples - 1)
                                                    : 0.37 + 0.5 * u;  // a profile for 1-D
          v = terrainAt(u, w) * (0.75 + 0.25 * std::cos(0.07 * sz)) + 3.0 * sz;
        }
        out[(size_t{z} * ny + y) * nx + x] = v;
      }
  return out;
}

// More levels than chooseLevels allows: padding up to a quarter of the samples.
int deepestLevels(uint32_t n, int order) {
  for (int levels = kMaxLevels; levels > 0; --levels) {
    AxisPlan p;
    if (makeAxisPlan(n, order, levels, &p) && (p.size(0) - n) * 4 <= n) return levels;
  }
  return 0;
}

GridPlan planFor(int dims, const uint32_t n[3], int order, bool deepest) {
  int levels[3] = {0, 0, 0};
  for (int a = 0; a < dims; ++a)
    levels[a] = deepest ? deepestLevels(n[a], order) : chooseLevels(n[a], order, kMaxLevels);
  GridPlan plan;
  EXPECT_TRUE(makeGridPlan(dims, n, order, levels, &plan));
  return plan;
}

struct Shape {
  int dims;
  uint32_t n[3];
};
const Shape kShapes[] = {
    {1, {1201, 1, 1}}, {2, {317, 460, 1}}, {3, {64, 64, 93}}, {3, {97, 101, 45}}};

double range(const std::vector<double>& v) {
  auto [lo, hi] = std::minmax_element(v.begin(), v.end());
  return *hi - *lo;
}

// --- perfect reconstruction ------------------------------------------------------

TEST(WaveletTransform, PerfectReconstruction) {
  for (const Shape& shape : kShapes)
    for (int k = kMinOrder; k <= kMaxOrder; ++k)
      for (bool deepest : {false, true})
        for (Data kind : {Data::kTerrain, Data::kRandom}) {
          const GridPlan plan = planFor(shape.dims, shape.n, k, deepest);
          const std::vector<double> input = makeData(plan, kind, 1000 + k);
          std::vector<double> data = input;
          analyze(plan, data.data());
          synthesize(plan, data.data());
          double err = 0.0;
          for (size_t i = 0; i < data.size(); ++i)
            err = std::max(err, std::fabs(data[i] - input[i]));
          EXPECT_LE(err, 1e-9 * range(input))
              << "order " << k << " dims " << shape.dims << " " << shape.n[0] << "x" << shape.n[1]
              << "x" << shape.n[2] << " levels " << plan.axis[0].levels << ","
              << plan.axis[1].levels << "," << plan.axis[2].levels
              << (kind == Data::kRandom ? " random" : " terrain");
        }
}

// The low-pass block left by a partial synthesis is the scaling block of the same
// data analysed to that level only.
TEST(WaveletTransform, PartialSynthesisGivesTheCoarserScalingBlock) {
  const uint32_t n[3] = {97, 101, 45};
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    const GridPlan plan = planFor(3, n, k, true);
    const std::vector<double> input = makeData(plan, Data::kTerrain, 5);
    std::vector<double> data = input;
    analyze(plan, data.data());
    for (int stop = 1; stop < plan.maxLevels(); ++stop) {
      std::vector<double> part = data;
      synthesize(plan, part.data(), stop);
      GridPlan shallow = plan;
      for (AxisPlan& a : shallow.axis)
        if (a.levels > stop) {
          a.coarse_intervals = a.intervals(stop);
          a.levels = stop;
        }
      std::vector<double> reference = input;
      analyze(shallow, reference.data());
      const Band top = bandsOf(shallow)[0];
      const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0);
      double err = 0.0;
      for (uint32_t z = 0; z < top.size[2]; ++z)
        for (uint32_t y = 0; y < top.size[1]; ++y)
          for (uint32_t x = 0; x < top.size[0]; ++x) {
            const size_t at = (size_t{z} * ny + y) * nx + x;
            err = std::max(err, std::fabs(part[at] - reference[at]));
          }
      EXPECT_LE(err, 1e-9 * range(input)) << "order " << k << " stop " << stop;
    }
  }
}

// --- dense 1-D check of the construction ------------------------------------------

using Dense = std::vector<std::vector<double>>;  // row-major

Dense multiply(const Dense& a, const Dense& b) {
  Dense c(a.size(), std::vector<double>(b[0].size(), 0.0));
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t l = 0; l < b.size(); ++l)
      if (a[i][l] != 0.0)
        for (size_t j = 0; j < b[0].size(); ++j) c[i][j] += a[i][l] * b[l][j];
  return c;
}

Dense identity(size_t n) {
  Dense m(n, std::vector<double>(n, 0.0));
  for (size_t i = 0; i < n; ++i) m[i][i] = 1.0;
  return m;
}

// Basis functions of one axis after full analysis, as columns of finest-level
// B-spline coefficients: scaling[j] for level j (j = 1..L), wavelet[j] for level j.
struct AxisBasis {
  std::vector<Dense> scaling, wavelet;
  Dense gram;  // of the finest B-splines, unit spacing
};

AxisBasis basisOf(const AxisPlan& axis) {
  AxisBasis basis;
  const int k = axis.order;
  const uint32_t f0 = axis.size(0);
  basis.gram.assign(f0, std::vector<double>(f0, 0.0));
  for (uint32_t i = 0; i < f0; ++i)
    for (uint32_t j = 0; j < f0; ++j) basis.gram[i][j] = gramEntry(k, axis.intervals(0), i, j);
  Dense to_finest = identity(f0);
  basis.scaling.push_back(to_finest);
  basis.wavelet.push_back({});
  for (int level = 1; level <= axis.levels; ++level) {
    const LevelFilters lf(k, axis.intervals(level));
    Dense p(lf.fine(), std::vector<double>(lf.coarse(), 0.0));
    Dense q(lf.fine(), std::vector<double>(lf.wavelets(), 0.0));
    for (uint32_t j = 0; j < lf.coarse(); ++j) {
      const Column c = lf.p(j);
      for (int r = 0; r < c.count; ++r) p[c.first_row + r][j] = c.taps[r];
    }
    for (uint32_t j = 0; j < lf.wavelets(); ++j) {
      const Column c = lf.q(j);
      for (int r = 0; r < c.count; ++r) q[c.first_row + r][j] = c.taps[r];
    }
    basis.wavelet.push_back(multiply(to_finest, q));
    to_finest = multiply(to_finest, p);
    basis.scaling.push_back(to_finest);
  }
  return basis;
}

double inner(const AxisBasis& b, const Dense& x, size_t i, const Dense& y, size_t j) {
  double s = 0.0;
  for (size_t r = 0; r < x.size(); ++r)
    if (x[r][i] != 0.0)
      for (size_t c = 0; c < y.size(); ++c) s += x[r][i] * b.gram[r][c] * y[c][j];
  return s;
}

TEST(WaveletTransform, WaveletsAreOrthogonalToEveryCoarserScalingFunction) {
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    const uint32_t n_min = static_cast<uint32_t>(minCoarseIntervals(k));
    for (uint32_t n0 : {n_min, n_min + 1, n_min + 5}) {
      AxisPlan axis;
      ASSERT_TRUE(makeAxisPlan(n0 * 8 + k - 1, k, 3, &axis));
      ASSERT_EQ(axis.coarse_intervals, n0);
      const AxisBasis b = basisOf(axis);
      for (int j = 1; j <= axis.levels; ++j)
        for (int m = j; m <= axis.levels; ++m) {
          const Dense& w = b.wavelet[j];
          const Dense& s = b.scaling[m];
          for (size_t i = 0; i < w[0].size(); ++i)
            for (size_t l = 0; l < s[0].size(); ++l) {
              const double norms = std::sqrt(inner(b, w, i, w, i) * inner(b, s, l, s, l));
              ASSERT_LE(std::fabs(inner(b, w, i, s, l)), 1e-12 * norms)
                  << "order " << k << " n0 " << n0 << " wavelet " << i << " of level " << j
                  << ", scaling function " << l << " of level " << m;
            }
        }
    }
  }
}

TEST(WaveletTransform, AxisBasisNormsAreTheL2NormsOfTheBasisFunctions) {
  for (int k = kMinOrder; k <= kMaxOrder; ++k) {
    AxisPlan axis;
    const uint32_t n0 = static_cast<uint32_t>(minCoarseIntervals(k)) + 2;
    ASSERT_TRUE(makeAxisPlan(n0 * 8 + k - 1, k, 3, &axis));
    const AxisBasis b = basisOf(axis);
    const std::vector<double> norms = axisBasisNorms(axis);
    ASSERT_EQ(norms.size(), axis.size(0));
    const int top = axis.levels;
    for (uint32_t i = 0; i < axis.size(top); ++i)
      EXPECT_NEAR(norms[i], std::sqrt(inner(b, b.scaling[top], i, b.scaling[top], i)),
                  1e-12 * norms[i]);
    for (int j = 1; j <= top; ++j)
      for (uint32_t i = 0; i < axis.size(j - 1) - axis.size(j); ++i)
        EXPECT_NEAR(norms[axis.size(j) + i], std::sqrt(inner(b, b.wavelet[j], i, b.wavelet[j], i)),
                    1e-12 * norms[axis.size(j) + i])
            << "order " << k << " level " << j << " wavelet " << i;
  }
  AxisPlan flat;
  ASSERT_TRUE(makeAxisPlan(10, 2, 0, &flat));
  EXPECT_EQ(axisBasisNorms(flat), std::vector<double>(10, 1.0));
}

// --- polynomials -----------------------------------------------------------------

// B-spline coefficients of p(x) = sum a[m] (x / scale)^m on the knots of `intervals`
// intervals with spacing `spacing`: the blossom of p at the d interior knots of each
// B-spline, e_m(t) / binomial(d, m) for x^m.
std::vector<double> polynomialCoefficients(int order, uint32_t intervals, double spacing,
                                           const std::vector<double>& a, double scale) {
  const int d = order - 1;
  std::vector<double> knots;
  for (int i = 0; i < d; ++i) knots.push_back(0.0);
  for (uint32_t m = 0; m <= intervals; ++m) knots.push_back(m * spacing / scale);
  for (int i = 0; i < d; ++i) knots.push_back(intervals * spacing / scale);
  std::vector<double> out(intervals + d);
  for (size_t i = 0; i < out.size(); ++i) {
    std::vector<double> e(d + 1, 0.0);  // elementary symmetric polynomials of t_{i+1..i+d}
    e[0] = 1.0;
    for (int r = 1; r <= d; ++r) {
      const double t = knots[i + r];
      for (int m = r; m >= 1; --m) e[m] += e[m - 1] * t;
    }
    double v = 0.0, binom = 1.0;
    for (int m = 0; m <= d && m < static_cast<int>(a.size()); ++m) {
      v += a[m] * e[m] / binom;
      binom = binom * (d - m) / (m + 1);
    }
    out[i] = v;
  }
  return out;
}

TEST(WaveletTransform, PolynomialsOfDegreeBelowTheOrderHaveNoDetail) {
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  for (const Shape& shape : kShapes)
    for (int k = kMinOrder; k <= kMaxOrder; ++k) {
      const GridPlan plan = planFor(shape.dims, shape.n, k, true);
      // A product of one polynomial of degree k-1 per axis, as finest coefficients.
      std::vector<double> factor[3], coarse[3];
      for (int a = 0; a < 3; ++a) {
        const AxisPlan& ax = plan.axis[a];
        std::vector<double> poly(k);
        for (double& c : poly) c = 300.0 * uni(rng);
        if (ax.levels == 0) {
          factor[a] = coarse[a] = std::vector<double>(ax.size(0), 1.0);
          continue;
        }
        const double scale = ax.intervals(0);
        factor[a] = polynomialCoefficients(k, ax.intervals(0), 1.0, poly, scale);
        coarse[a] = polynomialCoefficients(k, ax.coarse_intervals, std::ldexp(1.0, ax.levels),
                                           poly, scale);
      }
      const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0),
                     nz = plan.axis[2].size(0);
      std::vector<double> data(plan.paddedCount());
      for (uint32_t z = 0; z < nz; ++z)
        for (uint32_t y = 0; y < ny; ++y)
          for (uint32_t x = 0; x < nx; ++x)
            data[(size_t{z} * ny + y) * nx + x] = factor[0][x] * factor[1][y] * factor[2][z];
      const double tolerance = 1e-9 * range(data);
      analyze(plan, data.data());
      for (const Band& band : bandsOf(plan)) {
        double worst = 0.0;
        for (uint32_t z = 0; z < band.size[2]; ++z)
          for (uint32_t y = 0; y < band.size[1]; ++y)
            for (uint32_t x = 0; x < band.size[0]; ++x) {
              const uint32_t px = band.offset[0] + x, py = band.offset[1] + y,
                             pz = band.offset[2] + z;
              const double v = data[(size_t{pz} * ny + py) * nx + px];
              // The scaling block holds the polynomial's coarse B-spline coefficients.
              const double expected =
                  band.mask == 0 ? coarse[0][px] * coarse[1][py] * coarse[2][pz] : 0.0;
              worst = std::max(worst, std::fabs(v - expected));
            }
        EXPECT_LE(worst, tolerance) << "order " << k << " dims " << shape.dims << " band level "
                                    << band.level << " mask " << band.mask;
      }
    }
}

// --- fixed point against floating point ---------------------------------------------

// spec 4.7: a bound on |synthesizeFixed(2^16 c) / 2^16 - synthesize(c)| for integer
// coefficients c whose detail coefficients are at most `max_detail` in magnitude.
// Per 1-D pass the error grows by at most
//   rho = 1/2 (rounding) + 2^-25 * Qn * V  (rounding of the Q taps; V bounds the wavelet
//                                           inputs of the pass, in units of 2^-16)
// plus Qs times the error of the wavelet inputs, while the scaling inputs carry their
// error through P unchanged (P >= 0 with rows summing to 1, its taps exact in 24 bits).
double fixedFloatBound(const GridPlan& plan, double max_detail) {
  const int order = plan.axis[0].order;
  const double qs = orderFilters(order).max_row_q_sum;
  const double qn = orderFilters(order).max_row_q_count;
  const double c = max_detail * 65536.0;
  double e = 0.0;
  for (int level = plan.maxLevels(); level >= 1; --level) {
    int passes = 0;
    for (const AxisPlan& a : plan.axis) passes += a.levels >= level ? 1 : 0;
    for (int a = 0; a < passes; ++a) {
      const double v = std::pow(1.0 + qs, a) * (c + 1.0);
      const double rho = 0.5 + std::ldexp(qn * v, -25);
      e += std::pow(1.0 + qs, passes - 1 - a) * rho;
    }
  }
  return e / 65536.0;
}

TEST(WaveletTransform, FixedPointAgreesWithFloatingPoint) {
  std::mt19937_64 rng(4242);
  for (const Shape& shape : kShapes)
    for (int k = kMinOrder; k <= kMaxOrder; ++k) {
      const GridPlan plan = planFor(shape.dims, shape.n, k, true);
      // Integer coefficients: the terrain's own, quantised with step 1/4, and random ones.
      for (int which = 0; which < 2; ++which) {
        std::vector<double> coef = makeData(plan, Data::kTerrain, 1);
        if (which == 0) {
          analyze(plan, coef.data());
          for (double& v : coef) v = std::nearbyint(4.0 * v);
        } else {
          std::uniform_int_distribution<int> dist(-1000, 1000);
          for (double& v : coef) v = dist(rng);
        }
        const Band top = bandsOf(plan)[0];
        const uint32_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0);
        double max_detail = 0.0;
        for (size_t i = 0; i < coef.size(); ++i) {
          const uint32_t x = i % nx, y = (i / nx) % ny, z = static_cast<uint32_t>(i / nx / ny);
          const bool scaling = x < top.size[0] && y < top.size[1] && z < top.size[2];
          if (!scaling) max_detail = std::max(max_detail, std::fabs(coef[i]));
        }
        std::vector<int64_t> fixed(coef.size());
        for (size_t i = 0; i < coef.size(); ++i)
          fixed[i] = static_cast<int64_t>(coef[i]) * 65536;
        std::vector<double> real = coef;
        synthesize(plan, real.data());
        synthesizeFixed(plan, fixed.data());
        double err = 0.0, magnitude = 0.0;
        for (size_t i = 0; i < real.size(); ++i) {
          err = std::max(err, std::fabs(fixed[i] / 65536.0 - real[i]));
          magnitude = std::max(magnitude, std::fabs(real[i]));
        }
        const double bound = fixedFloatBound(plan, max_detail) + 1e-12 * magnitude;
        EXPECT_LE(err, bound) << "order " << k << " dims " << shape.dims;
        // The bound is worst-case; print how close it is for the record.
        if (k == 4 && shape.dims == 3 && which == 0)
          std::printf("  [fixed vs float] %ux%ux%u order 4: max error %.3g, bound %.3g "
                      "(max |detail| %.0f)\n",
                      shape.n[0], shape.n[1], shape.n[2], err, bound, max_detail);
      }
    }
}

}  // namespace
}  // namespace mrsv::wavelet
