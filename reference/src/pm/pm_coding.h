// The coding of the PM stream's values (spec 6.5, 6.7), written once as
// templates over the coder so that the encoder and the normative decoder
// cannot drift apart (the pattern of grid/coefficient_coding.h).
#pragma once

#include <cstdint>

#include "bitstream/range_coder_adapter.h"

namespace mrsv::pm {

constexpr int kMaxLengthModels = 32;

// spec 6.5.1 an adaptive integer code: the bit length of |v| in adaptive
// unary, the bit below the leading one adaptive, the rest equiprobable.
struct IntegerModels {
  BitModel length[kMaxLengthModels];
  BitModel first_low_bit[kMaxLengthModels];
  BitModel sign;
};

// Codes an unsigned value below 2^31. Returns false when a decoded length
// prefix reaches 31 bits (the stream is in error).
template <class Coder>
bool codeUnsigned(Coder& coder, IntegerModels& m, uint32_t* value) {
  // v + 1 >= 1 has n = floor(log2(v + 1)) bits below its leading one.
  uint32_t v1 = Coder::kEncoding ? *value + 1 : 0;
  int length = 0;
  if (Coder::kEncoding)
    while ((v1 >> (length + 1)) != 0) ++length;
  int n = 0;
  while (coder.bit(&m.length[n], n < length) != 0)
    if (++n == 31) return false;
  uint32_t low = 0;
  if (n > 0) {
    low = static_cast<uint32_t>(coder.bit(&m.first_low_bit[n], static_cast<int>((v1 >> (n - 1)) & 1)));
    if (n > 1) low = (low << (n - 1)) | coder.direct(v1 & ((1u << (n - 1)) - 1), n - 1);
  }
  *value = ((1u << n) | low) - 1;
  return true;
}

// Codes a signed value with |v| < 2^30: |v| as above, then the sign of a
// nonzero value. Returns false on a decoded magnitude of 2^30 or more.
template <class Coder>
bool codeSigned(Coder& coder, IntegerModels& m, int32_t* value) {
  uint32_t magnitude = 0;
  if (Coder::kEncoding) magnitude = *value < 0 ? 0u - static_cast<uint32_t>(*value) : *value;
  if (!codeUnsigned(coder, m, &magnitude)) return false;
  if (magnitude >= (1u << 30)) return false;
  int negative = 0;
  if (magnitude != 0) negative = coder.bit(&m.sign, Coder::kEncoding && *value < 0);
  *value = negative ? -static_cast<int32_t>(magnitude) : static_cast<int32_t>(magnitude);
  return true;
}

// spec 6.5.2 a value in [0, n) with n >= 1, in the truncated binary code
// (equiprobable bits; n = 1 takes no bits).
template <class Coder>
uint32_t codeTruncated(Coder& coder, uint32_t n, uint32_t value) {
  int k = 0;
  while ((2u << k) <= n) ++k;  // k = floor(log2 n)
  const uint32_t shorter = (2u << k) - n;  // this many values take k bits
  if (Coder::kEncoding) {
    if (value < shorter) {
      coder.direct(value, k);
    } else {
      coder.direct(value + shorter, k + 1);
    }
    return value;
  }
  uint32_t x = k > 0 ? coder.direct(0, k) : 0;
  if (x < shorter) return x;
  x = (x << 1) | coder.direct(0, 1);
  return x - shorter;
}

// spec 6.5.3 the bit models of a PM stream. PBAS uses `base_*`; the split
// models live across all PSPL chunks of the stream.
constexpr int kTurnContexts = 16;
constexpr uint8_t kFlagContexts = 16;
struct PmContexts {
  IntegerModels base_position[3];
  IntegerModels base_scalar;
  BitModel base_new_vertex[3];
  IntegerModels base_back_reference;

  BitModel split_flag[kFlagContexts];  // by min(neighbours, 15) of the vertex (6.7.1)
  IntegerModels arc_start[kTurnContexts];  // interior rings, by min(d, 15)
  IntegerModels turn[kTurnContexts];       // interior rings, by min(d, 15)
  BitModel boundary_kind[2];
  IntegerModels fan_faces;            // faces vt takes at a boundary edge
  IntegerModels fan_interior;         // b - a - 1 of a boundary vertex split inside its fan
  BitModel move_fine;                 // a move of vs in quantisation steps (6.7.3 step 1)
  IntegerModels vs_move[3];
  IntegerModels tangent_position[2];  // vt's two axes predicted by the centroid
  IntegerModels normal_position;      // vt's axis predicted by the plane
  IntegerModels scalar;
};

}  // namespace mrsv::pm
