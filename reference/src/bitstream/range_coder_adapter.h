// The range encoder in the shape codeArray() expects (encoder side only).
#pragma once

#include "bitstream/range_encoder.h"

namespace mrsv {

struct EncodingCoder {
  static constexpr bool kEncoding = true;
  RangeEncoder* rc;
  int bit(BitModel* m, int b) {
    rc->bit(m, b);
    return b;
  }
  uint32_t direct(uint32_t value, int n) {
    rc->direct(value, n);
    return value;
  }
};

}  // namespace mrsv
