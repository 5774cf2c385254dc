#include "grid/oracle.h"

#include <algorithm>
#include <cmath>

#include "wavelet/level_filters.h"
#include "wavelet/transform_float.h"

namespace mrsv {

AxisSupports::AxisSupports(const wavelet::AxisPlan& axis) {
  const int levels = axis.levels;
  scaling_lo_.resize(static_cast<size_t>(levels) + 1);
  scaling_hi_.resize(static_cast<size_t>(levels) + 1);
  wavelet_lo_.resize(static_cast<size_t>(levels) + 1);
  wavelet_hi_.resize(static_cast<size_t>(levels) + 1);
  // Level 0: the coefficients are the samples (padding beyond N maps to the last sample).
  const uint32_t n0 = axis.size(0);
  for (uint32_t i = 0; i < n0; ++i) {
    uint32_t s = std::min(i, axis.samples - 1);
    scaling_lo_[0].push_back(s);
    scaling_hi_[0].push_back(s);
  }
  // A coarse function is a combination of contiguous fine functions (one
  // column of P or Q): its support spans theirs.
  for (int l = 1; l <= levels; ++l) {
    const size_t fine = static_cast<size_t>(l - 1), coarse = static_cast<size_t>(l);
    const int64_t end = int64_t{axis.size(l - 1)} - 1;
    // A function combining the fine functions [first, last] (cut to the line).
    auto add = [&](int64_t first, int64_t last, std::vector<uint32_t>* lo, std::vector<uint32_t>* hi) {
      lo->push_back(scaling_lo_[fine][static_cast<size_t>(std::clamp<int64_t>(first, 0, end))]);
      hi->push_back(scaling_hi_[fine][static_cast<size_t>(std::clamp<int64_t>(last, 0, end))]);
    };
    if (wavelet::isCdf97(axis.order)) {
      // spec 4.11.3: low value i reaches fine positions 2i-3..2i+3, high value i
      // 2i-3..2i+5 (mirroring at the ends stays inside these once cut).
      for (int64_t i = 0; i < int64_t{axis.size(l)}; ++i)
        add(2 * i - 3, 2 * i + 3, &scaling_lo_[coarse], &scaling_hi_[coarse]);
      for (int64_t i = 0; i < int64_t{axis.size(l - 1) - axis.size(l)}; ++i)
        add(2 * i - 3, 2 * i + 5, &wavelet_lo_[coarse], &wavelet_hi_[coarse]);
      continue;
    }
    const wavelet::LevelFilters f(axis.order, axis.intervals(l));
    for (uint32_t j = 0; j < f.coarse(); ++j) {
      const wavelet::Column c = f.p(j);
      add(c.first_row, int64_t{c.first_row} + c.count - 1, &scaling_lo_[coarse], &scaling_hi_[coarse]);
    }
    for (uint32_t j = 0; j < f.wavelets(); ++j) {
      const wavelet::Column c = f.q(j);
      add(c.first_row, int64_t{c.first_row} + c.count - 1, &wavelet_lo_[coarse], &wavelet_hi_[coarse]);
    }
  }
}

void AxisSupports::scaling(int level, uint32_t index, uint32_t* lo, uint32_t* hi) const {
  *lo = scaling_lo_[static_cast<size_t>(level)][index];
  *hi = scaling_hi_[static_cast<size_t>(level)][index];
}

void AxisSupports::wavelet(int level, uint32_t index, uint32_t* lo, uint32_t* hi) const {
  *lo = wavelet_lo_[static_cast<size_t>(level)][index];
  *hi = wavelet_hi_[static_cast<size_t>(level)][index];
}

double regionWeight(const RegionOfInterest& roi, int num_dims, const uint32_t lo[3],
                    const uint32_t hi[3]) {
  // The point of the support box nearest to the region's centre.
  double p[3], q2 = 0, e2 = 0;
  for (int a = 0; a < num_dims; ++a) {
    p[a] = std::clamp(roi.center[a], static_cast<double>(lo[a]), static_cast<double>(hi[a]));
    double d = p[a] - roi.center[a];
    e2 += d * d;
    if (roi.ellipsoid) q2 += (d / roi.half_size[a]) * (d / roi.half_size[a]);
  }
  double distance = 0;
  if (roi.ellipsoid) {
    double q = std::sqrt(q2);
    if (q <= 1) return 1;
    distance = std::sqrt(e2) * (1 - 1 / q);  // along the ray to the centre
  } else {
    double d2 = 0;
    for (int a = 0; a < num_dims; ++a) {
      double d = std::max(0.0, std::fabs(p[a] - roi.center[a]) - roi.half_size[a]);
      d2 += d * d;
    }
    if (d2 == 0) return 1;
    distance = std::sqrt(d2);
  }
  double s = roi.falloff > 0 ? roi.falloff : 1e-9;
  return std::exp(-distance * distance / (2 * s * s));
}

namespace {

// The banded Gram matrix of one axis part of a band, row-major with 2*bw+1
// diagonals: entry (i, i + k - bw) at [i * (2 bw + 1) + k].
struct AxisGram {
  uint32_t n = 0;
  int bw = 0;
  std::vector<double> band;
};

AxisGram axisGram(const wavelet::AxisPlan& axis, int level, bool is_wavelet, uint32_t n) {
  AxisGram g;
  g.n = n;
  if (axis.levels == 0) {  // untransformed axis: the samples are independent
    g.bw = 0;
    g.band.assign(n, 1.0);
    return g;
  }
  g.bw = 2 * axis.order;
  const int width = 2 * g.bw + 1;
  g.band.assign(size_t{n} * static_cast<size_t>(width), 0.0);
  // Knot spacing 2^level at a scaling level, 2^(level-1) at the fine level of a wavelet level.
  const double spacing = std::ldexp(1.0, is_wavelet ? level - 1 : level);
  for (uint32_t i = 0; i < n; ++i)
    for (int k = 0; k < width; ++k) {
      int64_t j = int64_t{i} + k - g.bw;
      if (j < 0 || j >= n) continue;
      double v = is_wavelet
                     ? wavelet::waveletGramEntry(axis.order, axis.intervals(level), i, static_cast<uint32_t>(j))
                     : level == 0 ? (i == j ? 1.0 : 0.0)
                                  : wavelet::gramEntry(axis.order, axis.intervals(level), i,
                                                       static_cast<uint32_t>(j));
      g.band[size_t{i} * static_cast<size_t>(width) + static_cast<size_t>(k)] = spacing * v;
    }
  return g;
}

// y = (G along axis a) x over a box.
void applyAlongAxis(const AxisGram& g, const uint32_t box[3], int a, const std::vector<double>& x,
                    std::vector<double>* y) {
  y->assign(x.size(), 0.0);
  const size_t stride = a == 0 ? 1 : a == 1 ? box[0] : size_t{box[0]} * box[1];
  const int width = 2 * g.bw + 1;
  for (uint32_t z = 0; z < box[2]; ++z)
    for (uint32_t yy = 0; yy < box[1]; ++yy)
      for (uint32_t xx = 0; xx < box[0]; ++xx) {
        const uint32_t pos[3] = {xx, yy, z};
        const uint32_t i = pos[a];
        const size_t base = xx + box[0] * (yy + size_t{box[1]} * z) - i * stride;
        double sum = 0;
        for (int k = 0; k < width; ++k) {
          int64_t j = int64_t{i} + k - g.bw;
          if (j < 0 || j >= g.n) continue;
          sum += g.band[size_t{i} * static_cast<size_t>(width) + static_cast<size_t>(k)] *
                 x[base + static_cast<size_t>(j) * stride];
        }
        (*y)[base + i * stride] = sum;
      }
}

}  // namespace

double functionSpaceNormSquared(const wavelet::GridPlan& plan,
                                const std::vector<wavelet::Band>& bands,
                                const std::vector<double>& e) {
  if (wavelet::isCdf97(plan.axis[0].order)) {
    // No B-spline function space: the exact norm of the samples e synthesises to.
    std::vector<double> samples = e;
    wavelet::synthesize(plan, samples.data());
    double sum = 0;
    for (double v : samples) sum += v * v;
    return sum;
  }
  const uint64_t px = plan.axis[0].size(0), pxy = px * plan.axis[1].size(0);
  double total = 0;
  std::vector<double> x, y;
  for (const wavelet::Band& b : bands) {
    const uint32_t box[3] = {b.size[0], b.size[1], b.size[2]};
    x.resize(size_t{box[0]} * box[1] * box[2]);
    size_t k = 0;
    bool any = false;
    for (uint32_t z = 0; z < box[2]; ++z)
      for (uint32_t yy = 0; yy < box[1]; ++yy)
        for (uint32_t xx = 0; xx < box[0]; ++xx, ++k) {
          x[k] = e[(b.offset[0] + xx) + (b.offset[1] + yy) * px + (b.offset[2] + z) * pxy];
          any |= x[k] != 0;
        }
    if (!any) continue;
    std::vector<double> gx = x;
    for (int a = 0; a < 3; ++a) {
      const wavelet::AxisPlan& axis = plan.axis[a];
      if (box[a] == 1 && axis.levels == 0) continue;
      bool is_wavelet = (b.mask >> a) & 1;
      int level = is_wavelet ? b.level : (b.mask == 0 ? axis.levels : std::min(b.level, axis.levels));
      applyAlongAxis(axisGram(axis, level, is_wavelet, box[a]), box, a, gx, &y);
      gx.swap(y);
    }
    for (size_t i = 0; i < x.size(); ++i) total += x[i] * gx[i];
  }
  return total;
}

}  // namespace mrsv
