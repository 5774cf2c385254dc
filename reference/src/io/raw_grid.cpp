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


}  // namespace mrsv
