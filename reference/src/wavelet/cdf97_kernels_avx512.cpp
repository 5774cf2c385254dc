// The kernels of cdf97_kernels.h for x86-64 CPUs with AVX-512 F and DQ, eight
// int64 values per instruction. Compiled for the baseline x86-64 like the rest
// (the functions carry their own target attribute) and chosen at run time
// before the AVX2 ones.
//
// Why the results are those of the scalar kernels (cdf97_kernels.cpp), bit for
// bit: AVX-512 has the 64-bit operations the scalar code uses, lane by lane —
// the low 64 bits of a 64 x 64-bit product (_mm512_mullo_epi64, DQ; the
// product is exact since |c * s| < 2^62 by the kernels' preconditions, 4.11.4),
// the arithmetic (flooring) right shift (_mm512_srai_epi64) and the signed
// minimum and maximum that make sat. Values past the last multiple of eight go
// to the scalar kernels.
#include "wavelet/cdf97_kernels.h"

#include "wavelet/cdf97.h"
#include "wavelet/synthesis_fixed.h"  // kValueLimit

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MRSV_CDF97_AVX512 1
#include <immintrin.h>
#else
#define MRSV_CDF97_AVX512 0
#endif

namespace mrsv::wavelet {

#if MRSV_CDF97_AVX512
namespace {

#define MRSV_TARGET_AVX512 __attribute__((target("avx512f,avx512dq")))

MRSV_TARGET_AVX512 inline __m512i load(const int64_t* p) { return _mm512_loadu_si512(p); }
MRSV_TARGET_AVX512 inline void store(int64_t* p, __m512i v) { _mm512_storeu_si512(p, v); }

// The shift, min and max below are the zero-masked forms with every lane
// selected, the same operations: GCC 12's unmasked forms start from an
// "undefined" register that -Wmaybe-uninitialized reports (GCC bug 105593).
constexpr __mmask8 kAllLanes = 0xFF;

MRSV_TARGET_AVX512 inline __m512i sat(__m512i v) {
  return _mm512_maskz_max_epi64(
      kAllLanes, _mm512_maskz_min_epi64(kAllLanes, v, _mm512_set1_epi64(kValueLimit)),
      _mm512_set1_epi64(-kValueLimit));
}

// (c * s + 2^23) >> 24, the shift flooring.
MRSV_TARGET_AVX512 inline __m512i scaled(__m512i c, __m512i s) {
  const __m512i t = _mm512_add_epi64(_mm512_mullo_epi64(c, s),
                                     _mm512_set1_epi64(int64_t{1} << (kCdf97FracBits - 1)));
  return _mm512_maskz_srai_epi64(kAllLanes, t, kCdf97FracBits);
}

MRSV_TARGET_AVX512 bool scaleAvx512(const int64_t* x, int64_t* y, size_t n) {
  const __m512i k = _mm512_set1_epi64(kCdf97K);
  __m512i any = _mm512_setzero_si512();
  size_t j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m512i v = sat(scaled(k, sat(load(x + j))));
    any = _mm512_or_si512(any, v);
    store(y + j, v);
  }
  const bool tail = cdf97ScalarKernels().scale(x + j, y + j, n - j);
  return tail || _mm512_test_epi64_mask(any, any) != 0;
}

MRSV_TARGET_AVX512 bool saturateAvx512(const int64_t* x, int64_t* y, size_t n) {
  __m512i any = _mm512_setzero_si512();
  size_t j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m512i v = sat(load(x + j));
    any = _mm512_or_si512(any, v);
    store(y + j, v);
  }
  const bool tail = cdf97ScalarKernels().saturate(x + j, y + j, n - j);
  return tail || _mm512_test_epi64_mask(any, any) != 0;
}

MRSV_TARGET_AVX512 void liftAvx512(int64_t* y, const int64_t* a, const int64_t* b, size_t n,
                                   int64_t c) {
  const __m512i cv = _mm512_set1_epi64(c);
  size_t j = 0;
  for (; j + 8 <= n; j += 8) {
    const __m512i s = _mm512_add_epi64(load(a + j), load(b + j));
    store(y + j, sat(_mm512_sub_epi64(load(y + j), scaled(cv, s))));
  }
  cdf97ScalarKernels().lift(y + j, a + j, b + j, n - j, c);
}

MRSV_TARGET_AVX512 void interleaveAvx512(const int64_t* even, const int64_t* odd, int64_t* out,
                                         size_t n_even, size_t n_odd) {
  // Lane i of the result takes lane index[i] of (even, odd), odd's lanes numbered 8-15.
  const __m512i first = _mm512_set_epi64(11, 3, 10, 2, 9, 1, 8, 0);
  const __m512i second = _mm512_set_epi64(15, 7, 14, 6, 13, 5, 12, 4);
  size_t j = 0;
  for (; j + 8 <= n_odd; j += 8) {
    const __m512i e = load(even + j), o = load(odd + j);
    store(out + 2 * j, _mm512_permutex2var_epi64(e, first, o));        // e0 o0 ... e3 o3
    store(out + 2 * j + 8, _mm512_permutex2var_epi64(e, second, o));   // e4 o4 ... e7 o7
  }
  cdf97ScalarKernels().interleave(even + j, odd + j, out + 2 * j, n_even - j, n_odd - j);
}

}  // namespace

const Cdf97Kernels* cdf97Avx512Kernels() {
  static const Cdf97Kernels kernels{scaleAvx512, saturateAvx512, liftAvx512, interleaveAvx512,
                                    "avx512"};
  static const bool supported =
      __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq");
  return supported ? &kernels : nullptr;
}

#else

const Cdf97Kernels* cdf97Avx512Kernels() { return nullptr; }

#endif

}  // namespace mrsv::wavelet
