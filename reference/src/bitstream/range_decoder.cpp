#include "bitstream/range_decoder.h"

namespace mrsv {

RangeDecoder::RangeDecoder(const uint8_t* data, size_t size) : data_(data), size_(size) {
  // spec: 5.6 init: five bytes, the first of which the encoder always writes as 0.
  valid_start_ = nextByte() == 0;
  for (int i = 0; i < 4; ++i) code_ = (code_ << 8) | nextByte();
}

}  // namespace mrsv
