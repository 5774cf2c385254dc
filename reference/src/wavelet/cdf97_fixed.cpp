// spec: 4.11.3 fixed-point synthesis of the CDF 9/7 wavelet. Decode side:
// integers only.
//
// How the work is organised. None of it changes a result: within a step the
// updated values only read values of the other parity, and the lines of one
// pass are independent (4.11.3), so the order in which values and lines are
// computed is free; the steps, the scaling before them and the axis order are
// kept.
// - A line is held deinterleaved, as it arrives in the Mallat layout: its
//   even values x[2i] (the low half, scaled) in one array and its odd values
//   x[2i + 1] (the high half) in another. A step then updates one array from
//   the other at the same and the neighbouring index, which is one run of
//   neighbouring values: lowRows[i] -= C * (highRows[i - 1] + highRows[i]) for
//   the even steps, highRows[i] -= C * (lowRows[i] + lowRows[i + 1]) for the
//   odd ones. The line goes back to natural order when it is written.
// - Lines along x are contiguous: one line at a time, the runs along the line,
//   step after step, the mirrored ends of 4.11.3 copied to extra values before
//   each step. Lines along y and z are taken `width` neighbouring lines at a
//   time, row i of the batch holding value i of each line side by side, so the
//   runs go across the lines and each row is read from the grid as one block;
//   the four steps go as one sweep over the rows (synthesizeAcross), the
//   mirrored ends by the choice of row.
// - The x pass and the y pass of a level go slice by slice (z fixed): a line
//   along y reads only values of its slice, just written by the x pass of that
//   slice and still in cache.
// - Lines whose values are all 0 stay as they are: a 0 input gives 0 from the
//   scaling, and every step of 0 values gives sat(0 - ((C * 0 + 2^23) >> 24)) = 0.
//   When only the high half of a line along x is all 0 (at low rates, many
//   lines of the finer levels), the first step changes nothing and is left out.
// - The arithmetic on the runs is in cdf97_kernels.h: the scalar reference,
//   or an equivalent vectorised implementation.
#include <algorithm>
#include <climits>
#include <cstddef>
#include <cstring>
#include <vector>

#include "common/large_array.h"
#include "wavelet/cdf97.h"
#include "wavelet/cdf97_kernels.h"
#include "wavelet/synthesis_fixed.h"

namespace mrsv::wavelet {
namespace {

// `width` lines of f = size(j - 1) values each, deinterleaved (4.11.1: h =
// ceil(f / 2) even values, g = f - h odd ones): x[2i] of line w at low[i *
// width + w], x[2i + 1] at high[i * width + w]. Row h of low and rows -1 and g
// of high are the mirrored ends (filled by mirrorLow and mirrorHigh).
struct Lines {
  int64_t* low;   // rows 0 .. h
  int64_t* high;  // rows -1 .. g
  size_t h, g, width;
};

// Scratch for a batch of at most `rows` (= f) values per line.
struct Scratch {
  std::vector<int64_t> low, high;
  Lines lines(size_t f, size_t width) {
    const size_t h = (f + 1) / 2, g = f - h;
    if (low.size() < (h + 1) * width) low.resize((h + 1) * width);
    if (high.size() < (g + 2) * width) high.resize((g + 2) * width);
    return {low.data(), high.data() + width, h, g, width};
  }
};

// The right neighbour of the last odd value x[f - 1] when f is even is x[f - 2]
// (4.11.3: r = i - 1 when i + 1 = f): low row h = low row h - 1. When f is odd
// the last odd value x[f - 2] has x[f - 1] = low row h - 1 itself.
void mirrorLow(const Lines& l) {
  if (l.g == l.h)
    std::memcpy(l.low + l.h * l.width, l.low + (l.h - 1) * l.width, l.width * sizeof(int64_t));
}

// The left neighbour of x[0] is x[1] (4.11.3: l = i + 1 when i = 0): high row
// -1 = high row 0. The right neighbour of the last even value x[f - 1] when f
// is odd is x[f - 2]: high row g = high row g - 1.
void mirrorHigh(const Lines& l) {
  std::memcpy(l.high - l.width, l.high, l.width * sizeof(int64_t));
  if (l.g < l.h)
    std::memcpy(l.high + l.g * l.width, l.high + (l.g - 1) * l.width, l.width * sizeof(int64_t));
}

// spec: 4.11.3 step(0, D); step(1, G); step(0, B); step(1, A) on lines whose
// values are read (scaled and saturated). Step(0, C) at x[2i] reads x[2i - 1] =
// high row i - 1 and x[2i + 1] = high row i; step(1, C) at x[2i + 1] reads
// x[2i] = low row i and x[2i + 2] = low row i + 1. Without `high_nonzero` the
// caller knows the high rows are all 0, and step(0, D) changes nothing:
// sat(x - ((D * 0 + 2^23) >> 24)) = sat(x) = x.
void unliftLines(const Cdf97Kernels& k, const Lines& l, bool high_nonzero) {
  const size_t w = l.width;
  if (high_nonzero) {
    mirrorHigh(l);
    k.lift(l.low, l.high - w, l.high, l.h * w, kCdf97Delta);
  }
  mirrorLow(l);
  k.lift(l.high, l.low, l.low + w, l.g * w, kCdf97Gamma);
  mirrorHigh(l);
  k.lift(l.low, l.high - w, l.high, l.h * w, kCdf97Beta);
  mirrorLow(l);
  k.lift(l.high, l.low, l.low + w, l.g * w, kCdf97Alpha);
}

// One line along x of f values at `line` (contiguous), in place.
void synthesizeAlong(const Cdf97Kernels& k, int64_t* line, size_t f, Scratch* s) {
  const Lines l = s->lines(f, 1);
  const bool low = k.scale(line, l.low, l.h);             // value i of the line, i < h
  const bool high = k.saturate(line + l.h, l.high, l.g);  // value h + i of the line
  if (!low && !high) return;  // all 0 in, all 0 out
  unliftLines(k, l, high);
  k.interleave(l.low, l.high, line, l.h, l.g);
}

// `width` neighbouring lines along an axis with stride `stride`, f values each:
// value i of line w at base[i * stride + w], in place; or, with `emit`, row i
// of the result (value i of each line) goes to emit(i, row) instead (every row
// once, in some order).
//
// The lines are read into scratch first (row 2i of the result overwrites input
// row 2i, which is still to be read for i > 0). The four steps then run as one
// sweep over the rows instead of four: at stage t, step(0, D) at low row t,
// step(1, G) at high row t - 1, step(0, B) at low row t - 1, step(1, A) at high
// row t - 2, and rows 2(t - 2) and 2(t - 2) + 1 of the result are final and
// written. Each update finds its neighbours as that step needs them (step(0, D)
// at low row t reads high rows t - 1 and t before step(1, G) changes them,
// ...), so the values are those of the four separate steps; only the rows a
// stage touches are in use, and they stay in the first-level cache.
template <class Emit>
void synthesizeAcross(const Cdf97Kernels& k, int64_t* base, size_t stride, size_t f,
                      size_t width, Scratch* s, Emit&& emit) {
  const Lines l = s->lines(f, width);
  const size_t h = l.h, g = l.g, w = width;
  bool any = false;
  for (size_t i = 0; i < h; ++i) any |= k.scale(base + i * stride, l.low + i * w, w);
  for (size_t i = 0; i < g; ++i) any |= k.saturate(base + (h + i) * stride, l.high + i * w, w);
  if (!any) {  // all 0 in, all 0 out
    for (size_t i = 0; i < f; ++i) emit(i, l.low);  // l.low: all 0
    return;
  }
  // Row i of each half, the mirrored ends of 4.11.3 included: x[-1] = x[1]
  // (high row -1 is high row 0), x[f] = x[f - 2] (low row h is low row h - 1
  // when f is even, high row g is high row g - 1 when f is odd).
  auto low = [&](size_t i) { return l.low + (i < h ? i : h - 1) * w; };
  auto high = [&](ptrdiff_t i) {
    return l.high + (i < 0 ? 0 : static_cast<size_t>(i) < g ? static_cast<size_t>(i) : g - 1) * w;
  };
  for (size_t t = 0; t < h + 2; ++t) {
    const ptrdiff_t i = static_cast<ptrdiff_t>(t);
    if (t < h) k.lift(l.low + t * w, high(i - 1), high(i), w, kCdf97Delta);
    if (t >= 1 && t - 1 < g) k.lift(l.high + (t - 1) * w, low(t - 1), low(t), w, kCdf97Gamma);
    if (t >= 1 && t - 1 < h) k.lift(l.low + (t - 1) * w, high(i - 2), high(i - 1), w, kCdf97Beta);
    if (t >= 2 && t - 2 < g) k.lift(l.high + (t - 2) * w, low(t - 2), low(t - 1), w, kCdf97Alpha);
    if (t >= 2 && t - 2 < h) emit(2 * (t - 2), l.low + (t - 2) * w);
    if (t >= 2 && t - 2 < g) emit(2 * (t - 2) + 1, l.high + (t - 2) * w);
  }
}

// synthesizeAcross() writing back in place.
void synthesizeAcross(const Cdf97Kernels& k, int64_t* base, size_t stride, size_t f,
                      size_t width, Scratch* s) {
  const size_t bytes = width * sizeof(int64_t);
  synthesizeAcross(k, base, stride, f, width, s, [&](size_t i, const int64_t* row) {
    std::memcpy(base + i * stride, row, bytes);
  });
}

// Lines along y or z of f values are batched about kBatchValues / f at a time
// (at least 16, at most the width of the box): 2 x 256 KB of scratch, which
// stays in a 1-2 MB level-2 cache with the slice being worked on. Each row of a
// batch is then read and written as one long run. Narrow batches cost much
// more along z, whose rows lie a power of two apart and so fall into the same
// cache sets (measured on 256^3: 88 ms for the z pass of one level with 16
// lines a batch, 58 ms with 256).
constexpr size_t kBatchValues = size_t{1} << 16;
size_t batchWidth(size_t f, size_t box_width) {
  return std::min(box_width, std::max<size_t>(16, kBatchValues / f));
}

// The walk of 4.11.3; with `rows`, the last pass, when it runs along y or z,
// hands its rows to it (see cdf97.h). Returns whether it did.
bool synthesize(const GridPlan& plan, int64_t* data, int stop_level, const Cdf97Kernels& kernels,
                const SynthesisRows* rows, int start_level = INT_MAX) {
  if (!isValidGridPlan(plan)) return false;
  if (stop_level < 0) stop_level = 0;
  const size_t px = plan.axis[0].size(0), pxy = px * plan.axis[1].size(0);
  Scratch scratch;
  bool emitted = false;
  for (int level = std::min(plan.maxLevels(), start_level); level > stop_level; --level) {
    // spec: 4.11.3 the axes x, y, z in this order over the box of the level.
    size_t box[3];
    bool split[3];
    for (int a = 0; a < 3; ++a) {
      box[a] = plan.axis[a].size(level - 1);
      split[a] = plan.axis[a].levels >= level;
    }
    // Which pass, if any, goes to `rows`: the last one, if along y or z.
    const bool last = level == stop_level + 1 && rows != nullptr;
    const bool rows_y = last && split[1] && !split[2], rows_z = last && split[2];
    emitted = rows_y || rows_z;
    if (split[0] || split[1]) {
      for (size_t z = 0; z < box[2]; ++z) {
        int64_t* slice = data + z * pxy;
        if (split[0])
          for (size_t y = 0; y < box[1]; ++y) synthesizeAlong(kernels, slice + y * px, box[0], &scratch);
        if (split[1])
          for (size_t x = 0, bw = batchWidth(box[1], box[0]); x < box[0]; x += bw) {
            const size_t width = std::min(bw, box[0] - x);
            if (rows_y)
              synthesizeAcross(kernels, slice + x, px, box[1], width, &scratch,
                               [&](size_t y, const int64_t* row) {
                                 rows->row(rows->context, x, y, z, row, width);
                               });
            else
              synthesizeAcross(kernels, slice + x, px, box[1], width, &scratch);
          }
      }
    }
    if (split[2])
      for (size_t y = 0; y < box[1]; ++y)
        for (size_t x = 0, bw = batchWidth(box[2], box[0]); x < box[0]; x += bw) {
          const size_t width = std::min(bw, box[0] - x);
          if (rows_z)
            synthesizeAcross(kernels, data + y * px + x, pxy, box[2], width, &scratch,
                             [&](size_t z, const int64_t* row) {
                               rows->row(rows->context, x, y, z, row, width);
                             });
          else
            synthesizeAcross(kernels, data + y * px + x, pxy, box[2], width, &scratch);
        }
  }
  return emitted;
}

// The z pass of synthesizeAcross() turned into a stream over slices: stage t
// of its sweep needs low row t and high row t, which here are whole slices
// (z = t and z = h + t of the Mallat layout) synthesised along x and y just
// before, and finishes slices 2(t - 2) and 2(t - 2) + 1. The rows of a stage
// are one batch of lines along z as wide as a slice; the steps go over it a
// band of y rows at a time, so that the few rows a band touches stay in the
// first-level cache. A slice is needed from stage t to stage t + 2, so four
// slots of each parity suffice (the mirrored ends only ever name the slice
// next to the end, which is still held), or one per slice when there are
// fewer.
bool synthesizeLastLevel(const GridPlan& plan, const MallatRows& input, const Cdf97Kernels& k,
                         const SynthesisRows& rows) {
  if (!lastLevelBySlicesCdf97(plan)) return false;
  const size_t nx = plan.axis[0].size(0), ny = plan.axis[1].size(0), nz = plan.axis[2].size(0);
  const size_t h = (nz + 1) / 2, g = nz - h;  // 4.11.1
  const size_t plane = nx * ny;
  const size_t low_count = std::min<size_t>(4, h), high_count = std::min<size_t>(4, g);
  // Large for large slices, and a decoder must not throw: null when refused.
  const LargeArray<int64_t> slice = makeLargeArray<int64_t>(plane),
                            low_slots = makeLargeArray<int64_t>(uint64_t{low_count} * plane),
                            high_slots = makeLargeArray<int64_t>(uint64_t{high_count} * plane);
  if (!slice || !low_slots || !high_slots) return false;
  Scratch scratch;
  auto low = [&](size_t i) { return low_slots.get() + (i < h ? i : h - 1) % low_count * plane; };
  auto high = [&](ptrdiff_t i) {
    const size_t r = i < 0 ? 0 : static_cast<size_t>(i) < g ? static_cast<size_t>(i) : g - 1;
    return high_slots.get() + r % high_count * plane;
  };
  // Slice z of the Mallat layout synthesised along x, then along y (4.11.3, as
  // synthesize() does slice by slice), then read for the pass along z: scaled
  // when it is a low row, saturated when a high one, into `to`.
  auto prepare = [&](size_t z, bool low_row, int64_t* to) {
    for (size_t y = 0; y < ny; ++y) {
      int64_t* line = slice.get() + y * nx;
      input.row(input.context, y, z, line);
      synthesizeAlong(k, line, nx, &scratch);
    }
    for (size_t x = 0, bw = batchWidth(ny, nx); x < nx; x += bw) {
      const size_t width = std::min(bw, nx - x);
      synthesizeAcross(k, slice.get() + x, nx, ny, width, &scratch,
                       [&](size_t y, const int64_t* row) {
                         int64_t* dst = to + y * nx + x;
                         if (low_row) k.scale(row, dst, width);
                         else k.saturate(row, dst, width);
                       });
    }
  };
  const size_t band_rows = std::max<size_t>(1, 4096 / nx);
  for (size_t t = 0; t < h + 2; ++t) {
    const ptrdiff_t i = static_cast<ptrdiff_t>(t);
    if (t < h) prepare(t, true, low(t));
    if (t < g) prepare(h + t, false, high(i));
    for (size_t y0 = 0; y0 < ny; y0 += band_rows) {
      const size_t y1 = std::min(ny, y0 + band_rows), o = y0 * nx, n = (y1 - y0) * nx;
      if (t < h) k.lift(low(t) + o, high(i - 1) + o, high(i) + o, n, kCdf97Delta);
      if (t >= 1 && t - 1 < g) k.lift(high(i - 1) + o, low(t - 1) + o, low(t) + o, n, kCdf97Gamma);
      if (t >= 1 && t - 1 < h) k.lift(low(t - 1) + o, high(i - 2) + o, high(i - 1) + o, n, kCdf97Beta);
      if (t >= 2 && t - 2 < g) k.lift(high(i - 2) + o, low(t - 2) + o, low(t - 1) + o, n, kCdf97Alpha);
      for (size_t y = y0; y < y1; ++y) {
        if (t >= 2 && t - 2 < h) rows.row(rows.context, 0, y, 2 * (t - 2), low(t - 2) + y * nx, nx);
        if (t >= 2 && t - 2 < g)
          rows.row(rows.context, 0, y, 2 * (t - 2) + 1, high(i - 2) + y * nx, nx);
      }
    }
  }
  return true;
}

}  // namespace

void synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          const Cdf97Kernels& kernels) {
  synthesize(plan, data, stop_level, kernels, nullptr);
}

void synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level, int start_level) {
  synthesize(plan, data, stop_level, cdf97Kernels(), nullptr, start_level);
}

bool synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          const SynthesisRows& rows, int start_level) {
  return synthesize(plan, data, stop_level, cdf97Kernels(), &rows, start_level);
}

bool synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          const SynthesisRows& rows, const Cdf97Kernels& kernels) {
  return synthesize(plan, data, stop_level, kernels, &rows);
}

bool lastLevelBySlicesCdf97(const GridPlan& plan) {
  if (!isValidGridPlan(plan) || plan.num_dims != 3) return false;
  for (const AxisPlan& axis : plan.axis)
    if (axis.levels < 1 || !isCdf97(axis.order)) return false;
  return plan.axis[2].size(0) >= 2;  // a high row along z (4.11.1: g >= 1)
}

bool synthesizeLastLevelCdf97(const GridPlan& plan, const MallatRows& input,
                              const SynthesisRows& rows, const Cdf97Kernels& kernels) {
  return synthesizeLastLevel(plan, input, kernels, rows);
}

bool synthesizeLastLevelCdf97(const GridPlan& plan, const MallatRows& input,
                              const SynthesisRows& rows) {
  return synthesizeLastLevel(plan, input, cdf97Kernels(), rows);
}

}  // namespace mrsv::wavelet
