// Why the result is the scalar scan's (terrain_insertion.cpp), bit for bit:
// every operation is exact integer arithmetic on the same values. AVX2
// multiplies 32 x 32 -> 64 bits only (_mm256_mul_epi32, signed, from the low
// halves of the 64-bit lanes): the samples are 16-bit and den < 2^31, so the
// product is exact. The sums wrap modulo 2^64 like the scalar scan's unsigned
// arithmetic. AVX2 has no 64-bit absolute value or maximum: a compare against
// zero, an exclusive or and a subtraction; a compare and a blend. A first
// pass finds the largest |e| without a branch on the samples, a second the
// first sample that reaches it, as the scalar scan keeps the first of equals.
#include "reconstruct/run_scan.h"

#include <algorithm>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>

namespace mrsv::reconstruct {
namespace {

// |e| of the four samples from v, whose q is q4; lanes at or past `end`
// (a lane index) are -1.
__attribute__((target("avx2"))) inline __m256i sizes4(const int16_t* v, __m256i q4, __m256i den, __m256i lane,
                                                      __m256i end) {
  const __m256i value = _mm256_cvtepi16_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(v)));
  const __m256i e = _mm256_sub_epi64(_mm256_mul_epi32(value, den), q4);
  const __m256i sign = _mm256_cmpgt_epi64(_mm256_setzero_si256(), e);
  const __m256i size = _mm256_sub_epi64(_mm256_xor_si256(e, sign), sign);
  return _mm256_or_si256(size, _mm256_cmpgt_epi64(end, lane) ^ _mm256_set1_epi64x(-1));
}

// Calls visit(v, sizes) for every four samples from v along the runs, in
// order, sizes their |e| (sizes4()); stops at the first visit that returns
// true. Both passes below walk the runs so.
template <class Visit>
__attribute__((target("avx2"))) inline void forEachFour(const RunScan& s, Visit visit) {
  const __m256i den = _mm256_set1_epi64x(s.den);
  const __m256i steps = _mm256_set_epi64x(int64_t(3 * s.qx), int64_t(2 * s.qx), int64_t(s.qx), 0);
  const __m256i step4 = _mm256_set1_epi64x(int64_t(4 * s.qx));
  const __m256i lanes = _mm256_set_epi64x(3, 2, 1, 0);
  const __m256i four = _mm256_set1_epi64x(4);
  const int16_t* row = s.first_row;
  uint64_t q_row = s.q_row;
  for (int64_t r = 0; r < s.run_count; ++r, row += s.row_stride, q_row += s.dq_row) {
    const int64_t lo = s.runs[r].lo, hi = s.runs[r].hi;
    __m256i q4 = _mm256_add_epi64(_mm256_set1_epi64x(int64_t(q_row + s.qx * uint64_t(lo - s.x0))), steps);
    __m256i lane = lanes;
    const __m256i end = _mm256_set1_epi64x(hi - lo + 1);
    for (const int16_t *v = row + lo, *last = row + hi; v <= last; v += 4) {
      if (visit(v, sizes4(v, q4, den, lane, end))) return;
      q4 = _mm256_add_epi64(q4, step4);
      lane = _mm256_add_epi64(lane, four);
    }
  }
}

__attribute__((target("avx2"))) RunWorst scanRunsAvx2(const RunScan& s) {
  // The first pass: the largest |e|.
  __m256i worst = _mm256_set1_epi64x(0);
  forEachFour(s, [&](const int16_t*, __m256i size) __attribute__((target("avx2"))) {
    worst = _mm256_blendv_epi8(worst, size, _mm256_cmpgt_epi64(size, worst));
    return false;
  });
  alignas(32) int64_t w[4];
  _mm256_store_si256(reinterpret_cast<__m256i*>(w), worst);
  const int64_t size = std::max(std::max(w[0], w[1]), std::max(w[2], w[3]));
  if (size <= 0) return {0, nullptr};
  // The second: its first sample.
  const __m256i target = _mm256_set1_epi64x(size);
  const int16_t* at = nullptr;
  forEachFour(s, [&](const int16_t* v, __m256i sizes) __attribute__((target("avx2"))) {
    const int hit = _mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpeq_epi64(sizes, target)));
    if (hit) at = v + __builtin_ctz(unsigned(hit));
    return hit != 0;
  });
  return {size, at};
}

}  // namespace

RunScanFunction runScanAvx2() {
  static const bool supported = __builtin_cpu_supports("avx2");
  return supported ? scanRunsAvx2 : nullptr;
}

}  // namespace mrsv::reconstruct

#else

namespace mrsv::reconstruct {
RunScanFunction runScanAvx2() { return nullptr; }
}  // namespace mrsv::reconstruct

#endif
