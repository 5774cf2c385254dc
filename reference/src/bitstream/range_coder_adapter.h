// The range coder in the shape the coding templates expect (codeArray(),
// the PM records): one template body serves both directions.
#pragma once

#include "bitstream/range_decoder.h"
#include "bitstream/range_encoder.h"

namespace mrsv {

struct EncodingCoder {
  static constexpr bool kEncoding = true;
  RangeEncoder* rc;
  int bit(BitModel* m, int b) {
    rc->bit(m, b);
    return b;
  }
  int bitUnpredictable(BitModel* m, int b) { return bit(m, b); }
  int symbol(SymbolModel* m, int s) {
    rc->symbol(m, s);
    return s;
  }
  uint32_t direct(uint32_t value, int n) {
    rc->direct(value, n);
    return value;
  }
  bool overrun() const { return false; }
};

struct DecodingCoder {
  static constexpr bool kEncoding = false;
  RangeDecoder* rc;
  int bit(BitModel* m, int) { return rc->bit(m); }
  // The same decision as bit(), computed without a branch on its outcome.
  int bitUnpredictable(BitModel* m, int) { return rc->bitUnpredictable(m); }
  int symbol(SymbolModel* m, int) { return rc->symbol(m); }
  uint32_t direct(uint32_t, int n) { return rc->direct(n); }
  // Bytes were wanted past the payload: everything decoded since is garbage.
  bool overrun() const { return rc->overrun() != 0; }
};

}  // namespace mrsv
