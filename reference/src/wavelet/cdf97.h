// The CDF 9/7 biorthogonal wavelet by lifting (WHDR.order 5). spec: 4.11.
//
// The semi-orthogonal B-spline wavelets of the paper have a lower coding gain
// on smooth data than 9/7 (spec 5.9 item 5, tools/bench/transform_gain.py); this
// is the transform the codec offers beside them for rate-distortion. The grid
// plan, the Mallat layout and the bands are those of 4.3 and 4.4 with the sizes
// of 4.11; only the synthesis of one level differs.
#pragma once

#include <climits>
#include <cstddef>
#include <cstdint>

#include "wavelet/axis_plan.h"

namespace mrsv::wavelet {

// spec: 4.11.2 the lifting coefficients in fixed point, round(c * 2^24), and
// the real numbers they stand for (Daubechies and Sweldens' factorisation).
constexpr int kCdf97FracBits = 24;
constexpr int64_t kCdf97Alpha = -26610918;  // -1.586134342059924
constexpr int64_t kCdf97Beta = -888859;     // -0.052980118572961
constexpr int64_t kCdf97Gamma = 14812790;   //  0.882911075530934
constexpr int64_t kCdf97Delta = 7440810;    //  0.443506852043971
constexpr int64_t kCdf97K = 20638897;       //  1.230174104914001

// spec: 4.11.3. Fixed-point synthesis of every level above `stop_level`, the
// 9/7 counterpart of synthesizeFixed (which calls it for such plans); the
// same contract on `data`, saturation to +-kValueLimit included (start_level
// as there).
void synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          int start_level = INT_MAX);

// Where the last pass of a synthesis may put its results instead of `data`:
// row(context, x, y, z, values, n) receives the values of positions (x, y, z)
// to (x + n - 1, y, z) of the synthesised array (the low-pass block of
// `stop_level`, in the coordinates of the padded array), each position once.
struct SynthesisRows {
  void (*row)(void* context, size_t x, size_t y, size_t z, const int64_t* values, size_t n);
  void* context;
};

// synthesizeFixedCdf97() for a caller that only reads the result once (the
// decoder's sample mapping, spec 5.8.2): when the last pass runs along y or z,
// its rows go to `rows` as they are finished, not back to `data`, and the
// function returns true; `data` is then left with what that pass read. Returns
// false, with the whole result in `data` and `rows` not called, otherwise
// (the last pass along x, or nothing to synthesise).
bool synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          const SynthesisRows& rows, int start_level = INT_MAX);

// The values of level 1 in the Mallat layout (the low-pass block of level 1
// and the detail bands of level 1), given a row at a time: row(context, y, z,
// values) writes the size(0) values of row (y, z) along x of the padded array
// as synthesizeFixedCdf97() would find them there after synthesising every
// level above 1 (any int64: they are saturated as they are read).
struct MallatRows {
  void (*row)(void* context, size_t y, size_t z, int64_t* values);
  void* context;
};

// spec: 4.11.3 the last level, 1, of a 3-D plan split along all three axes
// at level 1, read from `input` rather than from a padded array, its results
// going to `rows` (each position once, in some order): the values the last
// pass of synthesizeFixedCdf97(plan, data, 0, rows) hands out. It needs no
// padded array, only a few slices in flight (at most 9 of size_x * size_y
// values). Returns false, calling neither, when the plan is not such a plan
// (then the caller synthesises a padded array): when
// !lastLevelBySlicesCdf97(plan); or when the memory for those slices cannot
// be had.
bool lastLevelBySlicesCdf97(const GridPlan& plan);
bool synthesizeLastLevelCdf97(const GridPlan& plan, const MallatRows& input,
                              const SynthesisRows& rows);

// Real-valued analysis and synthesis of one level along one axis (informative,
// the encoder's; transform_float.cpp walks the levels and axes): the exact
// inverse pair that 4.11.3 rounds, over a batch of `width` interleaved lines
// of `len` values (line_batches.h layout). Analysis: natural order in `x`
// (overwritten) to the low half, then the high half, in `out`; synthesis the
// reverse, `in` to natural order in `x`.
void analyzeCdf97Lines(double* x, double* out, size_t len, int width);
void synthesizeCdf97Lines(const double* in, double* x, size_t len, int width);

}  // namespace mrsv::wavelet
