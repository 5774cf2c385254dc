// spec: 5.7.6 the blocks of a blocked array.
#include "grid/precincts.h"

#include <algorithm>

#include "common/byte_reader.h"

namespace mrsv {

void blockGrid(const ArrayBox& box, const int resolution[3], int precinct_log2, uint32_t edge[3],
               uint32_t count[3]) {
  for (int a = 0; a < 3; ++a) {
    if (a >= box.num_dims) {
      edge[a] = box.size[a];
      count[a] = 1;
      continue;
    }
    const int shift = precinct_log2 - resolution[a];
    edge[a] = std::max(shift > 0 ? uint32_t{1} << shift : 1u, kMinBlockEdge);
    count[a] = static_cast<uint32_t>((uint64_t{box.size[a]} + edge[a] - 1) / edge[a]);
  }
}

ArrayBlock blockAt(const ArrayBox& box, const uint32_t edge[3], const uint32_t index[3]) {
  ArrayBlock b;
  b.box.num_dims = box.num_dims;
  for (int a = 0; a < 3; ++a) {
    b.origin[a] = index[a] * edge[a];
    b.box.size[a] = std::min(edge[a], box.size[a] - b.origin[a]);
  }
  return b;
}

uint64_t arrayBlockCount(const ArrayBox& box, const int resolution[3], int precinct_log2) {
  uint32_t edge[3], count[3];
  blockGrid(box, resolution, precinct_log2, edge, count);
  return uint64_t{count[0]} * count[1] * count[2];
}

std::vector<ArrayBlock> arrayBlocks(const ArrayBox& box, const int resolution[3], int precinct_log2) {
  uint32_t edge[3], count[3];
  blockGrid(box, resolution, precinct_log2, edge, count);
  std::vector<ArrayBlock> blocks;
  blocks.reserve(size_t{count[0]} * count[1] * count[2]);
  for (uint32_t k = 0; k < count[2]; ++k)
    for (uint32_t j = 0; j < count[1]; ++j)
      for (uint32_t i = 0; i < count[0]; ++i) {
        const uint32_t index[3] = {i, j, k};
        blocks.push_back(blockAt(box, edge, index));
      }
  return blocks;
}

bool blockOffsets(const uint8_t* table, uint64_t n, uint64_t coded_size, std::vector<uint64_t>* offsets) {
  offsets->resize(n + 1);
  (*offsets)[0] = 0;
  ByteReader r(table, 4 * n);
  for (uint64_t b = 0; b < n; ++b) (*offsets)[b + 1] = (*offsets)[b] + r.u32();
  return (*offsets)[n] == coded_size - 4 * n;
}

void bandResolution(int level, const int axis_levels[3], int resolution[3]) {
  for (int a = 0; a < 3; ++a) resolution[a] = std::min(level, axis_levels[a]);
}

}  // namespace mrsv
