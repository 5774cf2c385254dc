// The arithmetic of the CDF 9/7 fixed-point synthesis (spec 4.11.3) on spans of
// values: the scaling of the low-pass values, the reading of the high-pass
// values and one lifting step undone. Internal to the wavelet module
// (cdf97_fixed.cpp arranges the lines so that each of these is one run of
// neighbouring values).
//
// There is one portable implementation, cdf97ScalarKernels(), written as the
// formulas of 4.11.3 and the reference for every other one, and on x86-64 one
// for CPUs with AVX2 (cdf97_kernels_avx2.cpp) and one for CPUs with AVX-512 F
// and DQ (cdf97_kernels_avx512.cpp), the fastest chosen at run time. Every
// implementation gives the same integers as the scalar one for every input
// within the preconditions below (a unit test compares them on random values
// up to and beyond the saturation bound); the choice changes speed only.
#pragma once

#include <cstddef>
#include <cstdint>

#include "wavelet/axis_plan.h"
#include "wavelet/cdf97.h"

namespace mrsv::wavelet {

struct Cdf97Kernels {
  // y[j] = sat((K * sat(x[j]) + 2^23) >> 24) for j < n: a low-pass value as
  // read and scaled (4.11.3, first line of the loop). Any int64 x[j]. Returns
  // whether some y[j] is not 0 (exactly when some x[j] is not 0).
  bool (*scale)(const int64_t* x, int64_t* y, size_t n);
  // y[j] = sat(x[j]) for j < n: a high-pass value as read. Any int64 x[j].
  // Returns whether some y[j] is not 0.
  bool (*saturate)(const int64_t* x, int64_t* y, size_t n);
  // y[j] = sat(y[j] - ((c * (a[j] + b[j]) + 2^23) >> 24)) for j < n: step(p, C)
  // at the values y of one parity, a[j] and b[j] their two neighbours. Needs
  // |y[j]|, |a[j]|, |b[j]| <= kValueLimit and |c| < 2^26, so that |c * (a[j] +
  // b[j])| < 2^62 (4.11.4: all inputs of a step are saturated values; the
  // coefficients are below 2^24.67). y may not overlap a or b.
  void (*lift)(int64_t* y, const int64_t* a, const int64_t* b, size_t n, int64_t c);
  // out[2j] = even[j] for j < n_even, out[2j + 1] = odd[j] for j < n_odd, with
  // n_even - n_odd 0 or 1: a line back in natural order.
  void (*interleave)(const int64_t* even, const int64_t* odd, int64_t* out, size_t n_even,
                     size_t n_odd);
  const char* name;
};

// The reference implementation: plain C++, any CPU.
const Cdf97Kernels& cdf97ScalarKernels();
// The AVX2 implementation, or null when this build has none (not x86-64, or a
// compiler without target attributes) or this CPU lacks AVX2.
const Cdf97Kernels* cdf97Avx2Kernels();
// The AVX-512 implementation, likewise (needs AVX-512 F and DQ).
const Cdf97Kernels* cdf97Avx512Kernels();
// The fastest implementation this CPU runs (chosen once).
const Cdf97Kernels& cdf97Kernels();

// synthesizeFixedCdf97() of cdf97.h with the given kernels instead of
// cdf97Kernels(): the tests compare the implementations with it.
void synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          const Cdf97Kernels& kernels);
bool synthesizeFixedCdf97(const GridPlan& plan, int64_t* data, int stop_level,
                          const SynthesisRows& rows, const Cdf97Kernels& kernels);

bool synthesizeLastLevelCdf97(const GridPlan& plan, const MallatRows& input,
                              const SynthesisRows& rows, const Cdf97Kernels& kernels);

}  // namespace mrsv::wavelet
