#include "mrsv/raw_grid.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace mrsv {

void swapSampleBytes(std::vector<uint8_t>* samples, size_t sample_size) {
  if (sample_size <= 1) return;
  for (size_t i = 0; i + sample_size <= samples->size(); i += sample_size)
    std::reverse(samples->begin() + static_cast<long>(i),
                 samples->begin() + static_cast<long>(i + sample_size));
}

std::string parseDims(const std::string& text, GridHeader* header) {
  uint32_t sizes[3] = {1, 1, 1};
  int count = 0;
  size_t start = 0;
  while (true) {
    size_t comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos
                                                                      : comma - start);
    if (count == 3) return "at most three dimensions";
    if (item.empty() || item.size() > 9 ||
        item.find_first_not_of("0123456789") != std::string::npos)
      return "'" + item + "' is not a positive whole number";
    unsigned long v = std::strtoul(item.c_str(), nullptr, 10);
    if (v == 0) return "dimensions must be at least 1";
    sizes[count++] = static_cast<uint32_t>(v);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  header->num_dims = static_cast<uint8_t>(count);
  header->size_x = sizes[0];
  header->size_y = sizes[1];
  header->size_z = sizes[2];
  return {};
}

double sampleValue(const uint8_t* p, SampleType type) {
  uint64_t bits = 0;
  const size_t n = sampleSize(type);
  for (size_t i = 0; i < n; ++i) bits |= uint64_t{p[i]} << (8 * i);  // little-endian
  switch (type) {
    case SampleType::kUint8: return static_cast<double>(bits);
    case SampleType::kInt16: return static_cast<int16_t>(static_cast<uint16_t>(bits));
    case SampleType::kUint16: return static_cast<double>(bits);
    case SampleType::kInt32: return static_cast<int32_t>(static_cast<uint32_t>(bits));
    case SampleType::kFloat32: {
      uint32_t b = static_cast<uint32_t>(bits);
      float f;
      std::memcpy(&f, &b, 4);
      return f;
    }
    case SampleType::kFloat64: {
      double d;
      std::memcpy(&d, &bits, 8);
      return d;
    }
  }
  return 0;
}

}  // namespace mrsv
