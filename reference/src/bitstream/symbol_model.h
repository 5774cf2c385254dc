// Adaptive 16-symbol models for the range coder. spec: 5.6 (decode_symbol).
//
// A model divides 2^15 into 16 intervals, one per symbol, each at least
// kSymbolFloor wide so that every symbol stays codable. The adaptive part is
// cum[i], the share of the symbols below i out of kSymbolShares; symbol i
// has the interval [start(i), start(i + 1)) with start(i) = cum[i] +
// kSymbolFloor * i and start(16) = 2^15. A model learns fast at first (each
// cum[i] moves 1/32 of the way towards the symbol just coded, for its first 64
// symbols) and then slowly (1/128): measured on a CT volume (D29), this kept
// the binary coder's rate, which a fixed 1/32 or 1/64 did not.
#pragma once

#include <cstdint>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace mrsv {

constexpr int kSymbolCount = 16;
constexpr int kSymbolBits = 15;
constexpr uint32_t kSymbolFloor = 4;
constexpr uint32_t kSymbolShares = (1u << kSymbolBits) - kSymbolFloor * kSymbolCount;  // 32704
constexpr int kSymbolFastShift = 5, kSymbolSlowShift = 7;
constexpr uint16_t kSymbolFastCount = 64;

struct SymbolModel {
  uint16_t cum[kSymbolCount];  // cum[0] = 0 always
  uint16_t count = 0;          // symbols coded with the model, up to kSymbolFastCount

  // Each symbol starts about half as likely as the one before (the floor of
  // 4 flattens the tail): cum[i] =
  // floor(32704 * (2^16 - 2^(16 - i)) / (2^16 - 1)). Small magnitudes are the
  // common ones, and a uniform start cost small bands (St Helens at 0.5 bits
  // per sample: 57.37 against 57.46 dB).
  SymbolModel() {
    for (int i = 0; i < kSymbolCount; ++i)
      cum[i] = static_cast<uint16_t>(uint64_t{kSymbolShares} * ((1u << 16) - (1u << (16 - i))) / 0xFFFFu);
  }

  uint32_t start(int i) const {
    return i == kSymbolCount ? 1u << kSymbolBits : cum[i] + kSymbolFloor * static_cast<uint32_t>(i);
  }
  // The width of symbol s's interval, at least kSymbolFloor.
  uint32_t width(int s) const { return start(s + 1) - start(s); }

  // The largest s with start(s) <= q (start(0) = 0, so s >= 0), as the
  // specification says it.
  int findPlain(uint32_t q) const {
    int s = 0;
    for (int i = 1; i < kSymbolCount; ++i)
      if (start(i) <= q) s = i;
    return s;
  }

  // findPlain(), vectorised where SSE2 is available: the starts grow with s,
  // so those above q are a run at the end, found by one comparison of all 16.
  int find(uint32_t q) const {
#if defined(__SSE2__)
    const uint16_t q16 = static_cast<uint16_t>(q < 0x7FFFu ? q : 0x7FFFu);  // every start <= 2^15 - 4
    const __m128i steps_lo = _mm_setr_epi16(0, 4, 8, 12, 16, 20, 24, 28);
    const __m128i steps_hi = _mm_setr_epi16(32, 36, 40, 44, 48, 52, 56, 60);
    const __m128i* p = reinterpret_cast<const __m128i*>(cum);
    const __m128i lo = _mm_add_epi16(_mm_loadu_si128(p), steps_lo);
    const __m128i hi = _mm_add_epi16(_mm_loadu_si128(p + 1), steps_hi);
    const __m128i qv = _mm_set1_epi16(static_cast<short>(q16));
    const __m128i above = _mm_packs_epi16(_mm_cmpgt_epi16(lo, qv), _mm_cmpgt_epi16(hi, qv));
    return __builtin_ctz(static_cast<unsigned>(_mm_movemask_epi8(above)) | 0x10000u) - 1;
#else
    return findPlain(q);
#endif
  }

  // After symbol s: cum[i] moves 1/2^shift of the way to kSymbolShares for
  // i > s and to 0 for i <= s (each rounded down), as the specification says it.
  void adaptPlain(int s) {
    const int shift = nextShift();
    for (int i = 1; i < kSymbolCount; ++i) {
      const uint32_t c = cum[i];
      cum[i] = static_cast<uint16_t>(i > s ? c + ((kSymbolShares - c) >> shift) : c - (c >> shift));
    }
  }

  // adaptPlain(), vectorised where SSE2 is available.
  void adapt(int s) {
#if defined(__SSE2__)
    const int shift = nextShift();
    const __m128i index_lo = _mm_setr_epi16(0, 1, 2, 3, 4, 5, 6, 7);
    const __m128i index_hi = _mm_setr_epi16(8, 9, 10, 11, 12, 13, 14, 15);
    const __m128i sv = _mm_set1_epi16(static_cast<short>(s));
    const __m128i shares = _mm_set1_epi16(static_cast<short>(kSymbolShares));
    const __m128i by = _mm_cvtsi32_si128(shift);
    __m128i* p = reinterpret_cast<__m128i*>(cum);
    for (int half = 0; half < 2; ++half) {
      const __m128i c = _mm_loadu_si128(p + half);
      const __m128i above = _mm_cmpgt_epi16(half ? index_hi : index_lo, sv);
      const __m128i up = _mm_add_epi16(c, _mm_srl_epi16(_mm_sub_epi16(shares, c), by));
      const __m128i down = _mm_sub_epi16(c, _mm_srl_epi16(c, by));
      _mm_storeu_si128(p + half, _mm_or_si128(_mm_and_si128(above, up), _mm_andnot_si128(above, down)));
    }
#else
    adaptPlain(s);
#endif
  }

 private:
  // The adaptation rate of this update; counts it.
  int nextShift() {
    const int shift = count < kSymbolFastCount ? kSymbolFastShift : kSymbolSlowShift;
    count = static_cast<uint16_t>(count + (count < kSymbolFastCount));
    return shift;
  }
};

}  // namespace mrsv
