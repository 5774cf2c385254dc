// Adaptive range decoder. spec: 5.6 (entropy decoding).
//
// An arithmetic coder of bits with 11-bit adaptive probabilities and of
// 16-ary symbols (symbol_model.h), with a 32-bit
// range, byte-wise renormalisation and carry propagation in the encoder. All
// arithmetic is on unsigned 32-bit integers, so any byte string decodes to
// something (possibly garbage) without undefined behaviour; reading past the
// end of the payload yields zero bytes and is counted, so that the caller can
// report an overrun once per chunk (a sticky error, as in the byte reader).
#pragma once

#include <cstddef>
#include <cstdint>

#include "bitstream/symbol_model.h"

namespace mrsv {

constexpr int kProbabilityBits = 11;
constexpr uint16_t kProbabilityOne = 1u << kProbabilityBits;
constexpr uint16_t kProbabilityHalf = kProbabilityOne / 2;
constexpr int kAdaptShift = 5;

// The probability that the next bit is 0, in units of 2^-11; starts at one half.
struct BitModel {
  uint16_t p0 = kProbabilityHalf;
};

class RangeDecoder {
 public:
  RangeDecoder(const uint8_t* data, size_t size);

  // spec: 5.6 decode_bit(); adapts `model`.
  int bit(BitModel* model) {
    uint32_t bound = (range_ >> kProbabilityBits) * model->p0;
    int result;
    if (code_ < bound) {
      range_ = bound;
      model->p0 = static_cast<uint16_t>(model->p0 + ((kProbabilityOne - model->p0) >> kAdaptShift));
      result = 0;
    } else {
      code_ -= bound;
      range_ -= bound;
      model->p0 = static_cast<uint16_t>(model->p0 - (model->p0 >> kAdaptShift));
      result = 1;
    }
    normalize();
    return result;
  }

  // bit() computed without a branch on the decoded bit, for bits near one half
  // that a branch predictor cannot guess (signs, the bit below a leading one):
  // a mispredicted branch costs more than computing both outcomes.
  int bitUnpredictable(BitModel* model) {
    const uint32_t p0 = model->p0;
    const uint32_t bound = (range_ >> kProbabilityBits) * p0;
    const uint32_t b = code_ >= bound ? 1u : 0u;
    const uint32_t ones = 0u - b;  // all ones when the bit is 1
    code_ -= bound & ones;
    range_ = bound ^ ((bound ^ (range_ - bound)) & ones);
    const uint32_t if0 = p0 + ((kProbabilityOne - p0) >> kAdaptShift);
    const uint32_t if1 = p0 - (p0 >> kAdaptShift);
    model->p0 = static_cast<uint16_t>(if0 ^ ((if0 ^ if1) & ones));
    normalize();
    return static_cast<int>(b);
  }

  // spec: 5.6 decode_symbol(model): the largest s with start(s) * r <= code,
  // r = range >> 15. The test start(s) * r <= code is start(s) <= code / r
  // in integers, so one division leaves 16 small comparisons.
  int symbol(SymbolModel* model) {
    const uint32_t r = range_ >> kSymbolBits;
    const int s = model->find(code_ / r);
    const uint32_t low = model->start(s) * r;
    code_ -= low;
    range_ = s + 1 < kSymbolCount ? model->width(s) * r : range_ - low;
    model->adapt(s);
    normalize();
    return s;
  }

  // bit(&models[context(i)]) for i = from, from + 1, ... below end until a
  // bit is 1: returns that i, or end when every bit was 0. The same bits
  // and model updates as those bit() calls, with the coder's state held in
  // registers along the run: a loop of bit() calls around other work keeps
  // it in memory (a PT batch's split flags, 7.7.1: about 30 per split).
  template <class ContextOf>
  uint32_t firstOne(BitModel* models, uint32_t from, uint32_t end, ContextOf context) {
    uint32_t range = range_, code = code_;
    uint32_t i = from;
    for (; i < end; ++i) {
      BitModel& model = models[context(i)];
      const uint32_t p0 = model.p0;
      const uint32_t bound = (range >> kProbabilityBits) * p0;
      if (code >= bound) {
        code -= bound;
        range -= bound;
        model.p0 = static_cast<uint16_t>(p0 - (p0 >> kAdaptShift));
        range_ = range, code_ = code;
        normalize();
        return i;
      }
      range = bound;
      model.p0 = static_cast<uint16_t>(p0 + ((kProbabilityOne - p0) >> kAdaptShift));
      while (range < (1u << 24)) {
        range <<= 8;
        code = (code << 8) | nextByte();
      }
    }
    range_ = range, code_ = code;
    return end;
  }

  // spec: 5.6 decode_direct(n): n equiprobable bits, most significant first.
  uint32_t direct(int n) {
    uint32_t value = 0;
    while (n--) {
      range_ >>= 1;
      uint32_t b = code_ >= range_ ? 1u : 0u;
      code_ -= range_ & (0u - b);
      value = (value << 1) | b;
      normalize();
    }
    return value;
  }

  // Bytes wanted beyond the payload so far (0 for a well-formed stream).
  size_t overrun() const { return overrun_; }
  // Payload bytes read so far (a complete stream ends with consumed() == size).
  size_t consumed() const { return pos_; }
  // The first byte of every coded payload is 0 (spec 5.6); false otherwise.
  bool validStart() const { return valid_start_; }

 private:
  void normalize() {
    while (range_ < (1u << 24)) {
      range_ <<= 8;
      code_ = (code_ << 8) | nextByte();
    }
  }
  uint32_t nextByte() {
    if (pos_ < size_) return data_[pos_++];
    ++overrun_;
    return 0;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  size_t overrun_ = 0;
  uint32_t range_ = 0xFFFFFFFFu;
  uint32_t code_ = 0;
  bool valid_start_ = true;
};

}  // namespace mrsv
