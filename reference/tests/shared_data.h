// The real grids of ../shared/data (terrains and CT volumes), decompressed.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"

namespace mrsv::test {

struct SharedGrid {
  std::string name;        // file name without directory
  GridHeader header;       // sizes, num_dims and sample_type from the file name
  std::vector<uint8_t> samples;  // little-endian, as in the file
};

// Every *_<X>x<Y>[x<Z>]_<type>.raw.zst under terrain/ and volume/. Fails the
// current test when the directory is missing: the data is part of the test set-up.
std::vector<std::string> sharedGridFiles();
bool loadSharedGrid(const std::string& path, SharedGrid* out);

}  // namespace mrsv::test
