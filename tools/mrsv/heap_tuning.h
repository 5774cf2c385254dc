// The tools' heap, kept for reuse across tiles.
#pragma once

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrsv::cli {

// A tiled grid is coded a tile at a time, each tile allocating and freeing
// arrays of 0.1 to 8 MiB. glibc serves blocks of that size from mmap and gives
// them back on free, so each tile faults its memory in again: 72,000 page
// faults, a fifth of the time of a 256 x 256 x 1024 volume's decode in 64^3
// bricks. Below 8 MiB they now stay in the heap, and up to 16 MiB of free
// heap is kept. A library cannot make this choice for the programs that link
// it; the tools can.
inline void keepTileBuffersInTheHeap() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 8 << 20);
  mallopt(M_TRIM_THRESHOLD, 16 << 20);
#endif
}

}  // namespace mrsv::cli
