// Axis and grid plans of the B-spline wavelet transform: level sizes, padding,
// the Mallat layout and its band order. spec: 4.3, 4.4.
//
// Decode side: no Eigen, no floating point.
#pragma once

#include <cstdint>
#include <vector>

namespace mrsv::wavelet {

constexpr int kMinOrder = 1, kMaxOrder = 4;  // spec: 4.2 (Haar, linear, quadratic, cubic)
constexpr int kMaxLevels = 16;               // spec: 4.3
// spec: 4.11 the CDF 9/7 biorthogonal wavelet (JPEG 2000's irreversible one),
// selected by WHDR.order = 5: not a B-spline order, but it travels in the same
// field so that every plan, band list and layout rule stays one code path.
constexpr int kOrderCdf97 = 5;
inline bool isCdf97(int order) { return order == kOrderCdf97; }
inline bool isValidOrder(int order) {
  return (order >= kMinOrder && order <= kMaxOrder) || isCdf97(order);
}

// n_min(k): the fewest intervals a level may have (spec 4.3, table in 4.2).
// 0 for an order outside kMinOrder..kMaxOrder.
int minCoarseIntervals(int order);

// One axis: N samples become the finest-level B-spline coefficients (the samples
// themselves, padded at the high end to size(0) with values the encoder chooses).
// Level j = 0 is the finest, j = levels the coarsest; at level j there are
// coarse_intervals * 2^(levels - j) intervals and that + order - 1 coefficients.
// spec: 4.3
struct AxisPlan {
  uint32_t samples = 1;           // N
  int order = 1;                  // k
  int levels = 0;                 // L; 0 = this axis is not transformed
  uint32_t coarse_intervals = 0;  // n_0 = ceil((N - (k-1)) / 2^L) when L > 0 (so padding < 2^L)

  // Coefficients at level j; size(0) >= N is the padded length. Levels beyond
  // `levels` are the coarsest (this axis is not split there): size(j) ==
  // size(levels) for j > levels. With levels == 0 every size is N.
  uint32_t size(int level) const;
  // Intervals at level j (0 when levels == 0).
  uint32_t intervals(int level) const;
};

// False when levels > 0 and the plan is impossible (n_0 < n_min, N < k, levels > kMaxLevels,
// size(0) beyond 2^32 - 1), and for an order outside 1..4, N == 0 or levels < 0.
// With levels == 0: size(0) == N, no padding, coarse_intervals == 0. spec: 4.3
bool makeAxisPlan(uint32_t samples, int order, int levels, AxisPlan* out);

// Encoder's default: the most levels <= max_levels such that the plan is valid and the
// padding size(0) - N is at most N/32 (about 3 %); 0 if none. (Informative, spec 4.10.)
int chooseLevels(uint32_t samples, int order, int max_levels);

// spec: 4.4
struct GridPlan {
  int num_dims = 1;
  AxisPlan axis[3];  // unused axes: samples 1, levels 0
  int maxLevels() const;          // max over axes
  uint64_t paddedCount() const;   // product of axis[i].size(0)
};

// Convenience (added): a grid plan with every axis of `order`; axes at or beyond
// num_dims get samples 1 and levels 0. False when an axis plan is impossible.
bool makeGridPlan(int num_dims, const uint32_t samples[3], int order, const int levels[3],
                  GridPlan* out);

// Added: true when every axis is structurally sound: order 1..4, 0 <= levels <=
// kMaxLevels and, when levels > 0, coarse_intervals >= n_min(order) with size(0) below
// 2^32. Plans from makeAxisPlan always are; the transforms do nothing on other plans
// (they could not index the array safely).
bool isValidGridPlan(const GridPlan& plan);

// A subband in the Mallat layout of the padded array (x fastest, then y, then z).
// spec: 4.4
struct Band {
  int level;  // 1..maxLevels for detail bands (1 = finest); maxLevels for the coarsest scaling block too
  int mask;   // bit a set: axis a takes its wavelet part in this band; 0 = the coarsest scaling block
  uint32_t offset[3], size[3];  // box of the band in the padded array
};

// Coarse to fine: the scaling block first, then the detail bands of level maxLevels, ..., 1;
// within a level by increasing mask. An axis with fewer levels than the current level is not
// split at that level (it contributes only its scaling part to that level's bands).
// spec: 4.4
std::vector<Band> bandsOf(const GridPlan& plan);

}  // namespace mrsv::wavelet
