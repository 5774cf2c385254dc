// Adaptive range encoder of bits and 16-ary symbols, the inverse of
// RangeDecoder (spec 5.6).
#pragma once

#include <cstdint>
#include <vector>

#include "bitstream/range_decoder.h"

namespace mrsv {

class RangeEncoder {
 public:
  explicit RangeEncoder(std::vector<uint8_t>* out) : out_(out) {}

  void bit(BitModel* model, int bit) {
    uint32_t bound = (range_ >> kProbabilityBits) * model->p0;
    if (bit == 0) {
      range_ = bound;
      model->p0 = static_cast<uint16_t>(model->p0 + ((kProbabilityOne - model->p0) >> kAdaptShift));
    } else {
      low_ += bound;
      range_ -= bound;
      model->p0 = static_cast<uint16_t>(model->p0 - (model->p0 >> kAdaptShift));
    }
    normalize();
  }

  void symbol(SymbolModel* model, int s) {
    const uint32_t r = range_ >> kSymbolBits;
    const uint32_t low = model->start(s) * r;
    low_ += low;
    range_ = s + 1 < kSymbolCount ? model->width(s) * r : range_ - low;
    model->adapt(s);
    normalize();
  }

  void direct(uint32_t value, int n) {
    while (n--) {
      range_ >>= 1;
      if ((value >> n) & 1u) low_ += range_;
      normalize();
    }
  }

  // Writes the last bytes; the encoder must not be used afterwards.
  void finish() {
    for (int i = 0; i < 5; ++i) shiftLow();
  }

 private:
  void normalize() {
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      shiftLow();
    }
  }
  // Emits the top byte of `low_`, holding back 0xFF bytes until a carry is settled.
  void shiftLow() {
    if (static_cast<uint32_t>(low_) < 0xFF000000u || (low_ >> 32) != 0) {
      uint8_t carry = static_cast<uint8_t>(low_ >> 32);
      uint8_t temp = cache_;
      do {
        out_->push_back(static_cast<uint8_t>(temp + carry));
        temp = 0xFF;
      } while (--cache_size_ != 0);
      cache_ = static_cast<uint8_t>(low_ >> 24);
    }
    ++cache_size_;
    low_ = (low_ & 0x00FFFFFFu) << 8;
  }

  std::vector<uint8_t>* out_;
  uint64_t low_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint8_t cache_ = 0;
  uint64_t cache_size_ = 1;
};

}  // namespace mrsv
