// The kernels of cdf97_kernels.h for x86-64 CPUs with AVX2, four int64 values
// per instruction. Compiled for the baseline x86-64 like the rest (the
// functions carry their own target attribute) and chosen at run time, so the
// same binary runs on CPUs without AVX2, with the scalar kernels.
//
// Why the results are those of the scalar kernels (cdf97_kernels.cpp), bit for
// bit: every operation below is exact integer arithmetic on the same values.
// - The product c * s: AVX2 multiplies only 32 x 32 -> 64 bits
//   (_mm256_mul_epi32, signed, from the low halves of the 64-bit lanes). With
//   hi = floor((s + 2^31) / 2^32) and lo = s - hi * 2^32, lo is in [-2^31,
//   2^31) and is exactly the low half of s read as a signed 32-bit integer, so
//   c * s = (c * hi) * 2^32 + c * lo, both products exact. hi fits 32 bits
//   with room to spare: |s| <= 2 * kValueLimit < 2^36 in a step, |s| <=
//   kValueLimit in the scaling, and |c| < 2^25 (4.11.2), which also fits the
//   32 bits _mm256_mul_epi32 reads of it; c * s itself is below 2^61
//   (4.11.4), so the sum of the two products, computed modulo 2^64, is the
//   exact product.
// - The flooring shift (t >> 24 on int64): AVX2 shifts 64-bit lanes only
//   logically. The logical shift leaves t's sign in bit 39 and zeros above;
//   (u XOR 2^39) - 2^39 copies bit 39 into bits 40-63, which is the
//   arithmetic shift.
// - sat: AVX2 has no 64-bit min and max; a compare and a blend per bound.
#include "wavelet/cdf97_kernels.h"

#include "wavelet/cdf97.h"
#include "wavelet/synthesis_fixed.h"  // kValueLimit

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MRSV_CDF97_AVX2 1
#include <immintrin.h>
#else
#define MRSV_CDF97_AVX2 0
#endif

namespace mrsv::wavelet {

#if MRSV_CDF97_AVX2
namespace {

#define MRSV_TARGET_AVX2 __attribute__((target("avx2")))

static_assert(kCdf97FracBits == 24, "the shift emulation below is written for 24 bits");
static_assert(kValueLimit < (int64_t{1} << 35), "the product split below needs |s| < 2^36");

MRSV_TARGET_AVX2 inline __m256i load(const int64_t* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
MRSV_TARGET_AVX2 inline void store(int64_t* p, __m256i v) {
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(p), v);
}

// sat: clamp to [-kValueLimit, kValueLimit].
MRSV_TARGET_AVX2 inline __m256i sat(__m256i v) {
  const __m256i hi = _mm256_set1_epi64x(kValueLimit), lo = _mm256_set1_epi64x(-kValueLimit);
  v = _mm256_blendv_epi8(v, hi, _mm256_cmpgt_epi64(v, hi));
  return _mm256_blendv_epi8(v, lo, _mm256_cmpgt_epi64(lo, v));
}

// (c * s + 2^23) >> 24 with a flooring shift, for |s| < 2^36 and |c| < 2^26
// (c in every lane; |c * s| < 2^62): see the head of the file.
MRSV_TARGET_AVX2 inline __m256i scaled(__m256i c, __m256i s) {
  const __m256i hi = _mm256_srli_epi64(_mm256_add_epi64(s, _mm256_set1_epi64x(int64_t{1} << 31)), 32);
  const __m256i product =
      _mm256_add_epi64(_mm256_slli_epi64(_mm256_mul_epi32(c, hi), 32), _mm256_mul_epi32(c, s));
  const __m256i t = _mm256_add_epi64(product, _mm256_set1_epi64x(int64_t{1} << (kCdf97FracBits - 1)));
  const __m256i sign = _mm256_set1_epi64x(int64_t{1} << (63 - kCdf97FracBits));
  return _mm256_sub_epi64(_mm256_xor_si256(_mm256_srli_epi64(t, kCdf97FracBits), sign), sign);
}

MRSV_TARGET_AVX2 bool scaleAvx2(const int64_t* x, int64_t* y, size_t n) {
  const __m256i k = _mm256_set1_epi64x(kCdf97K);
  __m256i any = _mm256_setzero_si256();
  size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    const __m256i v = sat(scaled(k, sat(load(x + j))));
    any = _mm256_or_si256(any, v);
    store(y + j, v);
  }
  const bool tail = cdf97ScalarKernels().scale(x + j, y + j, n - j);
  return tail || !_mm256_testz_si256(any, any);
}

MRSV_TARGET_AVX2 bool saturateAvx2(const int64_t* x, int64_t* y, size_t n) {
  __m256i any = _mm256_setzero_si256();
  size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    const __m256i v = sat(load(x + j));
    any = _mm256_or_si256(any, v);
    store(y + j, v);
  }
  const bool tail = cdf97ScalarKernels().saturate(x + j, y + j, n - j);
  return tail || !_mm256_testz_si256(any, any);
}

MRSV_TARGET_AVX2 void liftAvx2(int64_t* y, const int64_t* a, const int64_t* b, size_t n,
                               int64_t c) {
  const __m256i cv = _mm256_set1_epi64x(c);
  size_t j = 0;
  for (; j + 4 <= n; j += 4) {
    const __m256i s = _mm256_add_epi64(load(a + j), load(b + j));
    store(y + j, sat(_mm256_sub_epi64(load(y + j), scaled(cv, s))));
  }
  cdf97ScalarKernels().lift(y + j, a + j, b + j, n - j, c);
}

MRSV_TARGET_AVX2 void interleaveAvx2(const int64_t* even, const int64_t* odd, int64_t* out,
                                     size_t n_even, size_t n_odd) {
  size_t j = 0;
  for (; j + 4 <= n_odd; j += 4) {
    const __m256i e = load(even + j), o = load(odd + j);
    const __m256i lo = _mm256_unpacklo_epi64(e, o);  // e0 o0 e2 o2
    const __m256i hi = _mm256_unpackhi_epi64(e, o);  // e1 o1 e3 o3
    store(out + 2 * j, _mm256_permute2x128_si256(lo, hi, 0x20));      // e0 o0 e1 o1
    store(out + 2 * j + 4, _mm256_permute2x128_si256(lo, hi, 0x31));  // e2 o2 e3 o3
  }
  cdf97ScalarKernels().interleave(even + j, odd + j, out + 2 * j, n_even - j, n_odd - j);
}

}  // namespace

const Cdf97Kernels* cdf97Avx2Kernels() {
  static const Cdf97Kernels kernels{scaleAvx2, saturateAvx2, liftAvx2, interleaveAvx2, "avx2"};
  static const bool supported = __builtin_cpu_supports("avx2");
  return supported ? &kernels : nullptr;
}

#else

const Cdf97Kernels* cdf97Avx2Kernels() { return nullptr; }

#endif

}  // namespace mrsv::wavelet
