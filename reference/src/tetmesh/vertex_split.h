// A vertex split of a tet complex and its inverse, the half-edge collapse.
// spec: 7.6.2 (the cut), 7.6.3 (the region), 7.6.4 (applying a split).
//
// A split of vs is given by a cut: a walk c_0, c_1, ... along the edges of the
// link of vs (a sphere when vs is interior, a disk when it is on the
// boundary). For an interior vs the walk is a simple cycle; for a boundary vs
// a simple path from the disk's boundary through its interior back to the
// boundary. The link triangles on the cut's sweep side (7.6.3) are the
// region: their tets move from vs to the new vertex vt, and each edge
// (c_i, c_i+1) of the cut gains the tet (vt, c_i, c_i+1, vs).
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "tetmesh/star_link.h"
#include "tetmesh/tet_complex.h"

namespace mrsv {

// The first n entries of *v set to 0 (v grown as needed). Up to 256 bytes
// the clear has a fixed size, which the compiler writes inline: a memset
// call for a link's few entries cost about 4 branch mispredictions per split
// on the CT crop (cachegrind).
template <class T>
T* zeroedPrefix(std::vector<T>* v, size_t n) {
  constexpr size_t kFixed = 256 / sizeof(T);
  if (v->size() < std::max(n, kFixed)) v->resize(std::max(n, kFixed));
  T* p = v->data();
  std::memset(p, 0, n <= kFixed ? 256 : n * sizeof(T));
  return p;
}

struct SplitScratch {
  std::vector<uint32_t> rotation;
  std::vector<uint32_t> walk_position;  // per local vertex: 1 + index in the walk, 0 if not on it (may be longer)
  std::vector<uint8_t> triangle_side;   // per link triangle: 0 unknown, 1 vt's, 2 vs's (may be longer)
  std::vector<uint32_t> queue;          // splitRegion(): the region's triangles in the order found
  std::vector<Diff3> difference;        // applyStarSplit(): per local vertex, its position - vt's
};

// spec 7.6.3: the tet slots of the link triangles on the sweep side of the
// walk (local vertices; `closed` for a cycle). Returns "" or the rule broken.
std::string splitRegion(const Link& link, const std::vector<uint32_t>& walk, bool closed,
                        SplitScratch* scratch, std::vector<uint32_t>* region_tets);
std::string splitRegion(const StarLink& link, const std::vector<uint32_t>& walk, bool closed,
                        SplitScratch* scratch, std::vector<uint32_t>* region_tets);

// spec 7.6.4: splits vs, whose new vertex vt already has its position and
// scalars (vt = the complex's last vertex, with no tets yet). `walk` lists
// vertex numbers. Checks every changed and new tet for orientation first and
// changes nothing when one is not positive. Returns "" or the rule broken.
std::string applySplit(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length,
                       bool closed, const uint32_t* moved, uint32_t moved_count);

// applySplit() again after undoSplit() undid it (7.6.5, moving to a finer
// level), without its checks: the split passed them when it was decoded and
// the positions have not changed since. `moved` is in increasing slot order
// (as the decoder records it), so the moved tets leave vs's list, in the
// same order, by one merged pass, not by reading each tet of it. (Moving up
// by applySplit() took 2.2 us per split on the CT crop, more than decoding
// it: 83 % of that was the pass over vs's tets and the orientation tests.)
void redoSplit(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length,
               bool closed, const uint32_t* moved, uint32_t moved_count);

// The exact inverse of the last split still in effect, lists in increasing
// slot order and `moved` too: the split's new tets, the last slots, are the
// last entries of their lists, and the moved tets go back into vs's list in
// order. (Appending them instead, as before, left lists out of order, and a
// later undo took the wrong entries off them: the tets stayed right, the
// lists did not, and decoding more batches after moving down and up failed.)
void undoSplit(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length,
               bool closed, const uint32_t* moved, uint32_t moved_count);

inline uint32_t cutEdgeCount(uint32_t walk_length, bool closed) { return closed ? walk_length : walk_length - 1; }
// The cut's position after i, i + 1 mod walk_length, without a division (a
// 32-bit divide per cut edge stood out in perf of the decoder's split).
inline uint32_t nextOnCut(uint32_t i, uint32_t walk_length) { return i + 1 == walk_length ? 0 : i + 1; }

}  // namespace mrsv
