// Bounds-checked little-endian reader over a borrowed byte range.
//
// The error is sticky (as in dav1d's bit reader): a read past the end returns
// zero and sets overrun(); parsers read a whole structure, then check once.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace mrsv {

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : data_(data), size_(size) {}

  uint8_t u8() { return static_cast<uint8_t>(take(1)); }
  uint16_t u16() { return static_cast<uint16_t>(take(2)); }
  uint32_t u32() { return static_cast<uint32_t>(take(4)); }
  uint64_t u64() { return take(8); }
  double f64() {
    uint64_t bits = u64();
    double value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }

  size_t position() const { return pos_; }
  size_t remaining() const { return overrun_ ? 0 : size_ - pos_; }
  bool overrun() const { return overrun_; }

 private:
  uint64_t take(size_t n) {
    if (overrun_ || size_ - pos_ < n) {
      overrun_ = true;
      pos_ = size_;
      return 0;
    }
    uint64_t value = 0;
    for (size_t i = 0; i < n; ++i) value |= uint64_t{data_[pos_ + i]} << (8 * i);
    pos_ += n;
    return value;
  }

  const uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
  bool overrun_ = false;
};

}  // namespace mrsv
