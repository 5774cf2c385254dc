// The decoder's storage for a grid whose last level is synthesised slice by
// slice (wavelet::synthesizeLastLevelCdf97): a 3-D 9/7 plan split along every
// axis at level 1, decoded at full resolution to integer samples. Internal to
// the grid decoder (wavelet_decode.cpp); nothing here changes a decoded value.
//
// Why: decoded the plain way, a 256^3 volume needs a padded array of 128 MiB of
// int64 coefficients, and most of the time not spent in the range decoder went
// to the kernel zeroing those fresh pages and to passes over them. Here
// - the levels above 1 live in a padded array of their own, that of the
//   "upper plan": the grid of level 1's low-pass block (an eighth of the
//   samples), with one level fewer on each axis; its bands have the same
//   offsets and sizes as in the whole plan, so they are decoded and
//   synthesised as always (the bands of 4.4 are the same boxes, 4.11.3 the
//   same passes over them);
// - the seven detail bands of level 1 are kept compact, each as its symbols in
//   16 bits when they all fit (2 bytes a value instead of 8, dequantised as
//   they are read), or else as its values;
// - level 1 is then synthesised from rows assembled from the two, a few slices
//   at a time, straight into the sample mapping.
// A 256^3 volume then decodes in about 77 MB (peak resident) instead of 158.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>

#include "common/large_array.h"
#include "wavelet/axis_plan.h"
#include "wavelet/cdf97.h"

namespace mrsv {

class LastLevelBands {
 public:
  // The storage for `plan`, or null when synthesizeLastLevelCdf97() does not
  // take the plan (then the whole padded array is synthesised).
  // The grid must be at least kMinDepth samples deep.
  static std::unique_ptr<LastLevelBands> make(const wavelet::GridPlan& plan);
  static constexpr uint32_t kMinDepth = 16;

  // The plan of the levels above 1, whose padded array holds every band of
  // level 2 and above at its offsets in the whole plan.
  const wavelet::GridPlan& upperPlan() const { return upper_; }

  // Storage for the detail band of level 1 with this mask (1 to 7), `count`
  // values (its box, x fastest), replacing any earlier; null when the memory
  // cannot be had. narrow(): the band's symbols, dequantised with `step` as
  // they are read (spec 5.4: sat(q * step) for |q| < 2^15). wide(): its values.
  int16_t* narrow(int mask, uint64_t count, uint64_t step);
  int64_t* wide(int mask, uint64_t count);

  // Level 1 in the Mallat layout, read from the stored bands (a band never
  // stored is 0) and from `low`, the upper plan's padded array synthesised
  // down to its level 0 (the low-pass block of level 1).
  wavelet::MallatRows rows(const int64_t* low);

 private:
  struct Band {
    LargeArray<int16_t> narrow;
    LargeArray<int64_t> wide;
    uint64_t step = 0;
  };
  static void row(void* self, size_t y, size_t z, int64_t* values);

  wavelet::GridPlan upper_;
  uint32_t low_size_[3] = {0, 0, 0};   // size(1) of each axis: the low-pass part
  uint32_t high_size_[3] = {0, 0, 0};  // size(0) - size(1): the wavelet part
  Band bands_[8];                      // by mask; [0] unused (the low-pass block is `low_`)
  const int64_t* low_ = nullptr;
};

}  // namespace mrsv
