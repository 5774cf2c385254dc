// The binary number types of VTK files (XML and legacy) and how to load one
// from bytes of either byte order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

namespace mrsv::tet_io {

enum class ValueType { kInt8, kUInt8, kInt16, kUInt16, kInt32, kUInt32, kInt64, kUInt64,
                       kFloat32, kFloat64 };

inline size_t valueSize(ValueType t) {
  switch (t) {
    case ValueType::kInt8: case ValueType::kUInt8: return 1;
    case ValueType::kInt16: case ValueType::kUInt16: return 2;
    case ValueType::kInt32: case ValueType::kUInt32: case ValueType::kFloat32: return 4;
    default: return 8;
  }
}

inline bool isFloatType(ValueType t) { return t == ValueType::kFloat32 || t == ValueType::kFloat64; }

// One value at `p` (valueSize(t) readable bytes). Integers also come out as
// `integer`; a UInt64 above INT64_MAX sets `integer` to -1 (never an index).
inline void loadValue(const uint8_t* p, ValueType t, bool big_endian, double* value,
                      int64_t* integer) {
  const size_t n = valueSize(t);
  uint64_t bits = 0;
  for (size_t i = 0; i < n; ++i) {
    uint64_t byte = p[big_endian ? i : n - 1 - i];
    bits = (bits << 8) | byte;
  }
  auto signExtend = [&](unsigned width) {
    uint64_t sign = uint64_t{1} << (width - 1);
    return static_cast<int64_t>((bits ^ sign) - sign);
  };
  switch (t) {
    case ValueType::kInt8: *integer = signExtend(8); break;
    case ValueType::kInt16: *integer = signExtend(16); break;
    case ValueType::kInt32: *integer = signExtend(32); break;
    case ValueType::kInt64: *integer = static_cast<int64_t>(bits); break;
    case ValueType::kUInt8: case ValueType::kUInt16: case ValueType::kUInt32:
      *integer = static_cast<int64_t>(bits);
      break;
    case ValueType::kUInt64:
      *integer = bits > static_cast<uint64_t>(INT64_MAX) ? -1 : static_cast<int64_t>(bits);
      *value = static_cast<double>(bits);
      return;
    case ValueType::kFloat32: {
      uint32_t b32 = static_cast<uint32_t>(bits);
      float f;
      std::memcpy(&f, &b32, 4);
      *value = f;
      *integer = 0;
      return;
    }
    case ValueType::kFloat64:
      std::memcpy(value, &bits, 8);
      *integer = 0;
      return;
  }
  *value = static_cast<double>(*integer);
}

}  // namespace mrsv::tet_io
