// spec: 4.3 axis plan, 4.4 grid plan, Mallat layout and band order.
#include "wavelet/axis_plan.h"

#include "wavelet/filter_tables.h"

namespace mrsv::wavelet {

int minCoarseIntervals(int order) {
  if (order < kMinOrder || order > kMaxOrder) return 0;
  return orderFilters(order).min_coarse_intervals;
}

uint32_t AxisPlan::size(int level) const {
  if (levels <= 0) return samples;
  int j = level < 0 ? 0 : level > levels ? levels : level;
  if (isCdf97(order)) return ((samples - 1) >> j) + 1;  // spec 4.11: ceil(N / 2^j), no padding
  // makeAxisPlan checked that size(0) fits, and the sizes decrease with j.
  return (coarse_intervals << (levels - j)) + static_cast<uint32_t>(order - 1);
}

uint32_t AxisPlan::intervals(int level) const {
  if (levels <= 0) return 0;
  int j = level < 0 ? 0 : level > levels ? levels : level;
  return coarse_intervals << (levels - j);
}

// spec: 4.3
bool makeAxisPlan(uint32_t samples, int order, int levels, AxisPlan* out) {
  if (!isValidOrder(order) || samples == 0) return false;
  if (levels < 0 || levels > kMaxLevels) return false;
  AxisPlan plan;
  plan.samples = samples;
  plan.order = order;
  plan.levels = levels;
  if (isCdf97(order)) {
    // spec: 4.11 every split level has at least 2 values: ceil(N / 2^(L-1)) >= 2.
    if (levels > 0 && ((samples - 1) >> (levels - 1)) + 1 < 2) return false;
  } else if (levels > 0) {
    const uint32_t d = static_cast<uint32_t>(order - 1);
    if (samples < static_cast<uint32_t>(order)) return false;
    // n_0 = ceil((N - d) / 2^L); 64-bit so that the padded length cannot wrap.
    const uint64_t step = uint64_t{1} << levels;
    const uint64_t n0 = (uint64_t{samples} - d + step - 1) / step;
    if (n0 < static_cast<uint64_t>(minCoarseIntervals(order))) return false;
    if ((n0 << levels) + d > UINT32_MAX) return false;
    plan.coarse_intervals = static_cast<uint32_t>(n0);
  }
  *out = plan;
  return true;
}

// spec: 4.10 (informative)
int chooseLevels(uint32_t samples, int order, int max_levels) {
  if (max_levels > kMaxLevels) max_levels = kMaxLevels;
  if (isCdf97(order)) {
    // The most levels that leave at least 8 values on the coarsest level: more
    // levels gain nothing measurable on the test data, fewer lose a little.
    int levels = 0;
    while (levels < max_levels && ((samples - 1) >> (levels + 1)) + 1 >= 8) ++levels;
    return levels;
  }
  for (int levels = max_levels; levels > 0; --levels) {
    AxisPlan plan;
    if (!makeAxisPlan(samples, order, levels, &plan)) continue;
    // padding <= N/32 exactly, without the rounding of an integer division.
    if (uint64_t{plan.size(0) - samples} * 32 <= samples) return levels;
  }
  return 0;
}

int GridPlan::maxLevels() const {
  int m = 0;
  for (int a = 0; a < 3; ++a) m = axis[a].levels > m ? axis[a].levels : m;
  return m;
}

uint64_t GridPlan::paddedCount() const {
  uint64_t count = 1;
  for (int a = 0; a < 3; ++a) count *= axis[a].size(0);
  return count;
}

bool makeGridPlan(int num_dims, const uint32_t samples[3], int order, const int levels[3],
                  GridPlan* out) {
  if (num_dims < 1 || num_dims > 3) return false;
  GridPlan plan;
  plan.num_dims = num_dims;
  for (int a = 0; a < 3; ++a) {
    bool used = a < num_dims;
    if (!makeAxisPlan(used ? samples[a] : 1, order, used ? levels[a] : 0, &plan.axis[a]))
      return false;
  }
  *out = plan;
  return true;
}

bool isValidGridPlan(const GridPlan& plan) {
  if (plan.num_dims < 1 || plan.num_dims > 3) return false;
  for (const AxisPlan& a : plan.axis) {
    if (!isValidOrder(a.order) || a.samples == 0) return false;
    if (a.levels < 0 || a.levels > kMaxLevels) return false;
    if (a.levels == 0) continue;
    if (isCdf97(a.order)) {
      if (((a.samples - 1) >> (a.levels - 1)) + 1 < 2) return false;
      continue;
    }
    if (a.coarse_intervals < static_cast<uint32_t>(minCoarseIntervals(a.order))) return false;
    if ((uint64_t{a.coarse_intervals} << a.levels) + (a.order - 1) > UINT32_MAX) return false;
  }
  return true;
}

// spec: 4.4
std::vector<Band> bandsOf(const GridPlan& plan) {
  const int top = plan.maxLevels();
  std::vector<Band> bands;
  Band scaling;
  scaling.level = top;
  scaling.mask = 0;
  for (int a = 0; a < 3; ++a) {
    scaling.offset[a] = 0;
    scaling.size[a] = plan.axis[a].size(top);
  }
  bands.push_back(scaling);
  for (int level = top; level >= 1; --level) {
    int split = 0;  // axes split at this level
    for (int a = 0; a < 3; ++a)
      if (plan.axis[a].levels >= level) split |= 1 << a;
    for (int mask = 1; mask < 8; ++mask) {
      if ((mask & ~split) != 0) continue;
      Band b;
      b.level = level;
      b.mask = mask;
      for (int a = 0; a < 3; ++a) {
        const AxisPlan& ax = plan.axis[a];
        if (mask & (1 << a)) {
          b.offset[a] = ax.size(level);
          b.size[a] = ax.size(level - 1) - ax.size(level);
        } else {
          b.offset[a] = 0;
          b.size[a] = ax.size(level);  // == size(levels) when the axis is not split here
        }
      }
      bands.push_back(b);
    }
  }
  return bands;
}

}  // namespace mrsv::wavelet
