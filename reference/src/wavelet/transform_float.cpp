// Floating-point analysis and synthesis. spec: 4.8, 4.9 (informative).
//
// One analysis step splits the fine coefficients c (2n + d of them, level j-1) into
// coarse coefficients c' (n + d) and wavelet coefficients w (n) with c = P c' + Q w.
// Multiplying by P^T G and Q^T G, where G is the Gram matrix of the fine B-splines,
// and using P^T G Q = 0 (semi-orthogonality):
//
//   (P^T G P) c' = P^T (G c),   (Q^T G Q) w = Q^T (G c).
//
// P^T G P is the Gram matrix of the coarse B-splines (twice the unit-spacing one),
// Q^T G Q that of the wavelets; both are banded and symmetric positive definite with
// condition numbers bounded independently of n (both bases are Riesz bases), so a
// banded LDL^T solve is accurate and the step takes linear time.
#include "wavelet/transform_float.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "wavelet/cdf97.h"
#include "wavelet/level_filters.h"
#include "wavelet/line_batches.h"

namespace mrsv::wavelet {

double gramEntry(int order, uint32_t intervals, uint32_t i, uint32_t j) {
  const OrderFilters& f = orderFilters(order);
  const int64_t d = f.gram_half_band;
  const int64_t last = int64_t{intervals} + d - 1;
  int64_t a = i, b = j;
  if (a - b > d || b - a > d || a > last || b > last) return 0.0;
  if (a + b > last) {  // the right half mirrors the left
    a = last - a;
    b = last - b;
  }
  if (a < f.gram_boundary_rows) return f.gram_boundary[a * (2 * d + 1) + (b - a + d)];
  if (b < f.gram_boundary_rows) return f.gram_boundary[b * (2 * d + 1) + (a - b + d)];
  return f.gram_band[a > b ? a - b : b - a];
}

double waveletGramEntry(int order, uint32_t coarse_intervals, uint32_t i, uint32_t j) {
  const LevelFilters f(order, coarse_intervals);
  const Column ci = f.q(i), cj = f.q(j);
  const uint32_t fine_intervals = 2 * coarse_intervals;
  const int64_t d = order - 1;
  double sum = 0.0;
  for (int r = 0; r < ci.count; ++r) {
    const int64_t row = int64_t{ci.first_row} + r;
    for (int s = 0; s < cj.count; ++s) {
      const int64_t col = int64_t{cj.first_row} + s;
      if (row - col > d || col - row > d) continue;
      sum += ci.taps[r] * cj.taps[s] *
             gramEntry(order, fine_intervals, static_cast<uint32_t>(row),
                       static_cast<uint32_t>(col));
    }
  }
  return sum;
}

namespace {

// A symmetric banded matrix kept as its lower band, row i holding A[i][i-o] for
// o = 0..bw (0 where i-o < 0). Every matrix here is Toeplitz away from its ends,
// so rows head_rows..tail_start-1 share one stored row: memory does not grow with n.
class SymBand {
 public:
  SymBand() = default;

  // row_fn(i, dst) writes the bw+1 band entries of row i. Rows [edge, n - edge)
  // must all equal row `edge`.
  template <typename RowFn>
  SymBand(uint32_t n, int bw, uint32_t edge, RowFn&& row_fn) : n_(n), bw_(bw) {
    const size_t w = static_cast<size_t>(bw) + 1;
    if (n <= 2 * edge + 1) {
      head_rows_ = tail_start_ = n;
    } else {
      head_rows_ = edge;
      tail_start_ = n - edge;
      inner_.resize(w);
      row_fn(edge, inner_.data());
    }
    head_.resize(head_rows_ * w);
    for (uint32_t i = 0; i < head_rows_; ++i) row_fn(i, &head_[i * w]);
    tail_.resize((n - tail_start_) * w);
    for (uint32_t i = tail_start_; i < n; ++i) row_fn(i, &tail_[(i - tail_start_) * w]);
  }

  uint32_t size() const { return n_; }
  int bandwidth() const { return bw_; }
  uint32_t headRows() const { return head_rows_; }
  uint32_t tailStart() const { return tail_start_; }

  const double* row(uint32_t i) const {
    const size_t w = static_cast<size_t>(bw_) + 1;
    if (i < head_rows_) return &head_[i * w];
    if (i < tail_start_) return inner_.data();
    return &tail_[(i - tail_start_) * w];
  }

  // y = A x for `width` interleaved vectors.
  void multiply(const double* x, double* y, size_t width) const {
    for (uint32_t i = 0; i < n_; ++i) {
      const double* a = row(i);
      double* yi = y + i * width;
      const double* xi = x + i * width;
      for (size_t l = 0; l < width; ++l) yi[l] = a[0] * xi[l];
      for (int o = 1; o <= bw_ && static_cast<uint32_t>(o) <= i; ++o) {
        const double* xo = x + (i - o) * width;
        for (size_t l = 0; l < width; ++l) yi[l] += a[o] * xo[l];
      }
      for (int o = 1; o <= bw_ && i + o < n_; ++o) {
        const double ao = row(i + o)[o];
        const double* xo = x + (i + o) * width;
        for (size_t l = 0; l < width; ++l) yi[l] += ao * xo[l];
      }
    }
  }

 private:
  uint32_t n_ = 0;
  int bw_ = 0;
  uint32_t head_rows_ = 0, tail_start_ = 0;
  std::vector<double> head_, inner_, tail_;
};

// A = L D L^T of a SymBand. Factor row i holds D[i], then L[i][i-o] for o = 1..bw.
// Inside the Toeplitz part of A the factor rows converge (geometrically) to a fixed
// row; once bw+1 consecutive rows agree to 2^-50 relatively, the rest of that part
// is taken to be that row, which changes the factor by rounding-level amounts only.
class BandLdlt {
 public:
  explicit BandLdlt(const SymBand& a) : n_(a.size()), bw_(a.bandwidth()) {
    const size_t w = static_cast<size_t>(bw_) + 1;
    tail_start_ = a.tailStart();
    head_.reserve(std::min<size_t>(n_, 256) * w);
    std::vector<double> cur(w);
    int same = 0;
    bool steady = false;
    for (uint32_t i = 0; i < n_; ++i) {
      if (steady && i < tail_start_) i = tail_start_;
      if (i >= n_) break;
      const double* ai = a.row(i);
      // L[i][j] for j = i-bw..i-1, then D[i]; L[i][m] for m < j is known by then.
      for (int o = bw_; o >= 1; --o) {
        if (static_cast<uint32_t>(o) > i) {
          cur[o] = 0.0;
          continue;
        }
        const uint32_t j = i - o;
        const double* lj = row(j);
        double s = ai[o];
        for (int p = o + 1; p <= bw_ && static_cast<uint32_t>(p) <= i; ++p)
          s -= cur[p] * row(i - p)[0] * lj[p - o];  // m = i - p: L[i][m] D[m] L[j][m]
        cur[o] = s / lj[0];
      }
      double dd = ai[0];
      for (int o = 1; o <= bw_ && static_cast<uint32_t>(o) <= i; ++o)
        dd -= cur[o] * cur[o] * row(i - o)[0];
      cur[0] = dd;
      if (i < tail_start_) {
        if (i > 0 && i > a.headRows() && close(cur.data(), &head_[(i - 1) * w])) {
          ++same;
        } else {
          same = 0;
        }
        head_.insert(head_.end(), cur.begin(), cur.end());
        head_rows_ = i + 1;
        if (same >= bw_ + 1 && i + 1 < tail_start_) {
          steady = true;
          inner_ = cur;
        }
      } else {
        tail_.insert(tail_.end(), cur.begin(), cur.end());
      }
    }
  }

  // Solves A x = b in place for `width` interleaved right-hand sides.
  void solve(double* x, size_t width) const {
    for (uint32_t i = 0; i < n_; ++i) {
      const double* li = row(i);
      double* xi = x + i * width;
      for (int o = 1; o <= bw_ && static_cast<uint32_t>(o) <= i; ++o) {
        const double* xo = x + (i - o) * width;
        for (size_t l = 0; l < width; ++l) xi[l] -= li[o] * xo[l];
      }
    }
    for (uint32_t i = 0; i < n_; ++i) {
      const double inv = 1.0 / row(i)[0];
      double* xi = x + i * width;
      for (size_t l = 0; l < width; ++l) xi[l] *= inv;
    }
    for (uint32_t i = n_; i-- > 0;) {
      double* xi = x + i * width;
      for (int o = 1; o <= bw_ && i + o < n_; ++o) {
        const double lo = row(i + o)[o];
        const double* xo = x + (i + o) * width;
        for (size_t l = 0; l < width; ++l) xi[l] -= lo * xo[l];
      }
    }
  }

 private:
  const double* row(uint32_t i) const {
    const size_t w = static_cast<size_t>(bw_) + 1;
    if (i < head_rows_) return &head_[i * w];
    if (i < tail_start_) return inner_.data();
    return &tail_[(i - tail_start_) * w];
  }
  bool close(const double* a, const double* b) const {
    for (int o = 0; o <= bw_; ++o)
      if (std::fabs(a[o] - b[o]) > std::ldexp(std::fabs(b[o]), -50)) return false;
    return true;
  }

  uint32_t n_;
  int bw_;
  uint32_t head_rows_ = 0, tail_start_ = 0;
  std::vector<double> head_, inner_, tail_;
};

// spec: 4.8. One level of one axis: fine level j-1 -> coarse level j.
class LevelAnalysis {
 public:
  LevelAnalysis(int order, uint32_t coarse_intervals)
      : filters_(order, coarse_intervals) {
    const uint32_t n = coarse_intervals;
    const int d = order - 1;
    const uint32_t edge = static_cast<uint32_t>(2 * d + 1);
    gram_fine_ = SymBand(filters_.fine(), d, edge, [&](uint32_t i, double* dst) {
      for (int o = 0; o <= d; ++o)
        dst[o] = static_cast<uint32_t>(o) <= i ? gramEntry(order, 2 * n, i, i - o) : 0.0;
    });
    // P^T G P: the coarse B-splines have knot spacing 2, twice the unit Gram.
    SymBand gram_coarse(filters_.coarse(), d, edge, [&](uint32_t i, double* dst) {
      for (int o = 0; o <= d; ++o)
        dst[o] = static_cast<uint32_t>(o) <= i ? 2.0 * gramEntry(order, n, i, i - o) : 0.0;
    });
    // Bandwidth of Q^T G Q: wavelets j < i interact when column j reaches within d
    // rows of column i's first row.
    int bw = 0;
    for (uint32_t i = 0, j = 0; i < filters_.wavelets(); ++i) {
      const Column ci = filters_.q(i);
      while (true) {
        const Column cj = filters_.q(j);
        if (int64_t{cj.first_row} + cj.count - 1 + d >= ci.first_row) break;
        ++j;
      }
      bw = std::max(bw, static_cast<int>(i - j));
    }
    SymBand gram_wavelet(filters_.wavelets(), bw, static_cast<uint32_t>(bw + 2 * d + 1),
                         [&](uint32_t i, double* dst) {
                           for (int o = 0; o <= bw; ++o)
                             dst[o] = static_cast<uint32_t>(o) <= i
                                          ? waveletGramEntry(order, n, i, i - o)
                                          : 0.0;
                         });
    coarse_ = std::make_unique<BandLdlt>(gram_coarse);
    wavelet_ = std::make_unique<BandLdlt>(gram_wavelet);
  }

  // in: fine() values per line (interleaved, `width` lines); out: coarse() scaling
  // coefficients then wavelets() wavelet coefficients. `in` is overwritten with G c.
  void run(double* in, double* out, std::vector<double>* scratch, int width) const {
    const size_t w = static_cast<size_t>(width);
    const uint32_t coarse = filters_.coarse(), wavelets = filters_.wavelets();
    scratch->resize(size_t{filters_.fine()} * w);
    double* y = scratch->data();
    gram_fine_.multiply(in, y, w);
    auto dot = [&](const Column& col, double* dst) {
      for (size_t l = 0; l < w; ++l) dst[l] = 0.0;
      const double* src = y + col.first_row * w;
      for (int r = 0; r < col.count; ++r, src += w)
        for (size_t l = 0; l < w; ++l) dst[l] += col.taps[r] * src[l];
    };
    for (uint32_t j = 0; j < coarse; ++j) dot(filters_.p(j), out + j * w);
    for (uint32_t j = 0; j < wavelets; ++j) dot(filters_.q(j), out + (coarse + j) * w);
    coarse_->solve(out, w);
    wavelet_->solve(out + coarse * w, w);
  }

 private:
  LevelFilters filters_;
  SymBand gram_fine_;
  std::unique_ptr<BandLdlt> coarse_, wavelet_;
};

// c = P c' + Q w for a batch of lines, with the exact (double) taps.
void synthesizeBatch(const LevelFilters& f, const double* in, double* out, int width) {
  const size_t w = static_cast<size_t>(width);
  for (size_t i = 0; i < size_t{f.fine()} * w; ++i) out[i] = 0.0;
  auto add = [&](const Column& col, const double* value) {
    double* acc = out + col.first_row * w;
    for (int r = 0; r < col.count; ++r, acc += w)
      for (size_t l = 0; l < w; ++l) acc[l] += col.taps[r] * value[l];
  };
  for (uint32_t j = 0; j < f.coarse(); ++j) add(f.p(j), in + j * w);
  for (uint32_t j = 0; j < f.wavelets(); ++j) add(f.q(j), in + (f.coarse() + j) * w);
}

void paddedSizes(const GridPlan& plan, uint32_t padded[3]) {
  for (int a = 0; a < 3; ++a) padded[a] = plan.axis[a].size(0);
}

}  // namespace

// spec: 4.8. Level by level from the finest; within a level z, y, x (the reverse of
// synthesis; the axes commute, so any order gives the same result up to rounding).
void analyze(const GridPlan& plan, double* data) {
  if (!isValidGridPlan(plan)) return;
  uint32_t padded[3];
  paddedSizes(plan, padded);
  std::vector<double> in, out, scratch;
  for (int level = 1; level <= plan.maxLevels(); ++level) {
    uint32_t box[3];
    for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(level - 1);
    for (int a = 2; a >= 0; --a) {
      const AxisPlan& axis = plan.axis[a];
      if (axis.levels < level) continue;
      if (isCdf97(axis.order)) {  // spec 4.11.5
        forEachLineBatch(padded, box, a, data, &in, &out, [&](double* src, double* dst, int width) {
          analyzeCdf97Lines(src, dst, box[a], width);
        });
        continue;
      }
      const LevelAnalysis step(axis.order, axis.intervals(level));
      forEachLineBatch(padded, box, a, data, &in, &out,
                       [&](double* src, double* dst, int width) {
                         step.run(src, dst, &scratch, width);
                       });
    }
  }
}

void synthesize(const GridPlan& plan, double* data, int stop_level) {
  if (!isValidGridPlan(plan)) return;
  if (stop_level < 0) stop_level = 0;
  uint32_t padded[3];
  paddedSizes(plan, padded);
  std::vector<double> in, out;
  for (int level = plan.maxLevels(); level > stop_level; --level) {
    uint32_t box[3];
    for (int a = 0; a < 3; ++a) box[a] = plan.axis[a].size(level - 1);
    for (int a = 0; a < 3; ++a) {
      const AxisPlan& axis = plan.axis[a];
      if (axis.levels < level) continue;
      if (isCdf97(axis.order)) {  // spec 4.11.5
        forEachLineBatch(padded, box, a, data, &in, &out, [&](double* src, double* dst, int width) {
          synthesizeCdf97Lines(src, dst, box[a], width);
        });
        continue;
      }
      const LevelFilters filters(axis.order, axis.intervals(level));
      forEachLineBatch(padded, box, a, data, &in, &out,
                       [&](double* src, double* dst, int width) {
                         synthesizeBatch(filters, src, dst, width);
                       });
    }
  }
}

// spec: 4.9
std::vector<double> axisBasisNorms(const AxisPlan& axis) {
  std::vector<double> norms(axis.size(0), 1.0);
  GridPlan check;
  check.axis[0] = axis;
  if (axis.levels <= 0 || !isValidGridPlan(check)) return norms;
  if (isCdf97(axis.order)) {
    // No function space here: the norm of the samples one coefficient
    // synthesises to, the same for every coefficient of a band (taken from one
    // in its middle; the few at the ends differ a little).
    auto bandNorm = [&](uint32_t first, uint32_t end) {
      std::vector<double> line(axis.size(0), 0.0);
      line[(first + end) / 2] = 1.0;
      synthesize(check, line.data());
      double e = 0;
      for (double v : line) e += v * v;
      std::fill(norms.begin() + first, norms.begin() + end, std::sqrt(e));
    };
    bandNorm(0, axis.size(axis.levels));
    for (int level = axis.levels; level >= 1; --level) bandNorm(axis.size(level), axis.size(level - 1));
    return norms;
  }
  const int top = axis.levels;
  // Scaling functions of the coarsest level: knot spacing 2^L.
  const double coarse_scale = std::ldexp(1.0, top);
  for (uint32_t i = 0; i < axis.size(top); ++i)
    norms[i] = std::sqrt(coarse_scale * gramEntry(axis.order, axis.intervals(top), i, i));
  // Wavelets of level j are combinations of the level j-1 B-splines (spacing 2^(j-1)).
  for (int level = top; level >= 1; --level) {
    const double scale = std::ldexp(1.0, level - 1);
    const uint32_t n = axis.intervals(level);
    const uint32_t first = axis.size(level);
    // Interior wavelets all have the same norm; compute the boundary ones and one interior.
    const uint32_t edge = static_cast<uint32_t>(orderFilters(axis.order).q_boundary) + 1;
    double interior = 0.0;
    for (uint32_t i = 0; i < n; ++i) {
      double g;
      if (i < edge || i + edge >= n) {
        g = waveletGramEntry(axis.order, n, i, i);
      } else {
        if (interior == 0.0) interior = waveletGramEntry(axis.order, n, i, i);
        g = interior;
      }
      norms[first + i] = std::sqrt(scale * g);
    }
  }
  return norms;
}

}  // namespace mrsv::wavelet
