// spec: 5.7.6 blocked arrays. With WHDR.precinct_log2 = P > 0, every coded array
// of a wavelet-coded grid (band, mask, residual) is cut into blocks that are
// entropy coded apart, each block covering at most a precinct of 2^P samples
// per axis at full resolution: a reader of a box of the grid decodes only the
// blocks whose coefficients reach it, while the transform stays one transform
// of the whole grid (decision D90).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "grid/coefficient_coding.h"
#include "mrsv/grid.h"

namespace mrsv {

// The least block edge: the coarse levels' blocks cover more than a precinct
// rather than a handful of coefficients each.
constexpr uint32_t kMinBlockEdge = 16;

// One block: its first position in the array's box and its own box.
struct ArrayBlock {
  uint32_t origin[3];
  ArrayBox box;
};

// The blocks of an array over `box` whose positions along axis a are
// 2^resolution[a] samples apart, in raster order (x fastest). Edge along a used
// axis: max(2^P >> resolution[a], kMinBlockEdge); the last block of an axis is
// shorter. P > 0.
std::vector<ArrayBlock> arrayBlocks(const ArrayBox& box, const int resolution[3], int precinct_log2);

// spec 5.7.6 rule 2: from the table of `n` u32 lengths at `table` (4n bytes)
// of a blocked array of `coded_size` bytes, offsets[b] .. offsets[b + 1]
// (n + 1 entries, offsets[n] their sum): block b's bytes, counted from the
// end of the table. False when the sum is not coded_size - 4n.
bool blockOffsets(const uint8_t* table, uint64_t n, uint64_t coded_size, std::vector<uint64_t>* offsets);

// Scratch of a decoder of blocked arrays, kept from array to array.
struct BlockScratch {
  std::vector<int64_t> values;
  std::vector<uint8_t> skip;
  std::vector<uint64_t> offsets;
};

// The block edge and the number of blocks along each axis (block (i, j, k) is
// number i + count[0] * (j + count[1] * k), starting at i * edge[0], ...).
void blockGrid(const ArrayBox& box, const int resolution[3], int precinct_log2, uint32_t edge[3],
               uint32_t count[3]);

// Block `index` of that grid (index[a] < count[a]).
ArrayBlock blockAt(const ArrayBox& box, const uint32_t edge[3], const uint32_t index[3]);

// How many blocks arrayBlocks() gives, without making them: a decoder checks
// the table of lengths against it first (spec 5.7.6 rule 1).
uint64_t arrayBlockCount(const ArrayBox& box, const int resolution[3], int precinct_log2);

// The resolution of a band's coefficients along each axis: min(level, L_a).
void bandResolution(int level, const int axis_levels[3], int resolution[3]);

// Copies block `b` of an array stored at `data` (value (x, y, z) at
// data[x + y * row + z * slice]) to a contiguous `out` of b.box.count() entries.
template <class T>
void copyBlockOut(const T* data, size_t row, size_t slice, const ArrayBlock& b, T* out) {
  const T* base = data + b.origin[0] + b.origin[1] * row + b.origin[2] * slice;
  for (uint32_t z = 0; z < b.box.size[2]; ++z)
    for (uint32_t y = 0; y < b.box.size[1]; ++y) {
      const T* src = base + y * row + z * slice;
      for (uint32_t x = 0; x < b.box.size[0]; ++x) *out++ = src[x];
    }
}

// The reverse: a contiguous block into its place.
template <class T>
void copyBlockIn(const T* in, const ArrayBlock& b, T* data, size_t row, size_t slice) {
  T* base = data + b.origin[0] + b.origin[1] * row + b.origin[2] * slice;
  for (uint32_t z = 0; z < b.box.size[2]; ++z)
    for (uint32_t y = 0; y < b.box.size[1]; ++y) {
      T* dst = base + y * row + z * slice;
      for (uint32_t x = 0; x < b.box.size[0]; ++x) dst[x] = *in++;
    }
}

}  // namespace mrsv
