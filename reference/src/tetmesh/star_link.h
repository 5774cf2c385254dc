// The link of a vertex as a PT decoder walks it: only what cut() and the
// region need (spec 7.6.1 to 7.6.3), built in one pass over the star.
// spec: 7.6.1 (links, rotation), 7.6.3 (the region's steps across edges).
//
// Link (tet_complex.h) builds every rotation of every link vertex up front
// for the manifold checks of 7.4 and the encoder. A decoded split visits the
// rotations of only its cut's few vertices, so StarLink keeps the link's
// directed edges in a table instead and follows them on demand: next(p, x)
// is one lookup. Links of up to 64 vertices (all but a few in practice: the
// CT crop's mean is 17) index a 64 x 64 table of packed entries (stamp,
// triangle, third vertex) whose stamp says they belong to this build, so
// nothing is cleared between splits; larger ones hash.
//
// Local vertex numbers are given in the order the star first meets the
// vertices, not by ascending vertex number as in Link: sorting them cost a
// tenth of the build and the second pass that renumbers the triangles
// (issue 21's profile). The few places where 7.7.2 ranks link vertices by
// number ask for it: localOfRank() (c_0), boundaryVertices() (p_0's list),
// rotationFromLowest(). Its other members and methods answer as Link's do, so
// the coding templates and splitRegion() run on either.
//
// Shortcuts resting on spec 7.3 (every level is a manifold whose vertex
// links are spheres or disks): a link with F = 2m - 4 triangles on m
// vertices is a sphere and has no boundary edge (a disk has F = 2m - 2 - B,
// B >= 3 boundary edges), so only other links are scanned edge by edge; and
// no directed edge is held by two triangles, so the dense table keeps the
// last one written without testing for an earlier one (the hashed table,
// for large links, keeps the first, as Link does).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "tetmesh/tet_complex.h"

namespace mrsv {

struct StarLink {
  uint32_t center = 0;
  std::vector<uint32_t> vertices;                  // vertex numbers, in the order the star meets them
  std::vector<std::array<uint32_t, 3>> triangles;  // local indices, Link's order
  std::vector<uint32_t> triangle_tet;              // the tet slot of each triangle
  std::vector<uint8_t> on_boundary;                // per local vertex: an edge with one triangle (set only when has_boundary)
  bool has_boundary = false;

  // The triangle holding the directed edge a -> b (written (a, b, ...)), or -1.
  int64_t triangleFrom(uint32_t a, uint32_t b) const {
    const uint32_t e = find(a, b);
    return e == kNone ? -1 : static_cast<int64_t>(triangleOf(e));
  }
  // triangleFrom() for hot loops: the triangle holding a -> b, or kNoTriangle.
  static constexpr uint32_t kNoTriangle = UINT32_MAX;
  uint32_t triangleHolding(uint32_t a, uint32_t b) const {
    const uint32_t e = find(a, b);
    return e == kNone ? kNoTriangle : triangleOf(e);
  }
  // triangleHolding() with the table's base and stamp held by the caller:
  // in a loop that stores bytes (the region's flood) the compiler would
  // reload both from the StarLink at every lookup.
  struct Lookup {
    const StarLink* link;
    const uint32_t* dense;  // nullptr: the hashed table
    uint32_t stamp;
    uint32_t shift;
    uint32_t triangleHolding(uint32_t a, uint32_t b) const {
      if (dense == nullptr) return link->triangleHolding(a, b);
      const uint32_t e = dense[a << shift | b];
      return e >> 16 == stamp ? (e >> 8) & 0xFF : kNoTriangle;
    }
  };
  Lookup lookup() const { return Lookup{this, dense_used_ ? dense_.data() : nullptr, edge_stamp_, dense_shift_}; }
  // The triangle across the edge from triangle f's j-th vertex to its next
  // one (it holds that edge reversed), or -1 on the link's boundary.
  int64_t across(uint32_t f, int j) const { return triangleFrom(triangles[f][(j + 1) % 3], triangles[f][j]); }
  // As Link::rotation (spec 7.6.1): p's neighbours in order around it from
  // `start`, or from the start of the fan when p is a boundary vertex.
  bool rotation(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const;
  // rotation(p, its link neighbour of smallest vertex number): c_0's of 7.7.2.
  bool rotationFromLowest(uint32_t p, std::vector<uint32_t>* out) const;
  // The same two for cut(): the rotation in the first entries of `out`,
  // which only grows (no fill, no push_back per entry: callgrind had them
  // at half the cost of the rotations), and its length, 0 when it fails.
  uint32_t rotationInto(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const;
  uint32_t rotationFromLowestInto(uint32_t p, std::vector<uint32_t>* out) const;
  // The local vertex of rank r (0 = the smallest vertex number), r < m.
  uint32_t localOfRank(uint32_t r) const;
  // The boundary vertices of the link, by ascending vertex number.
  void boundaryVertices(std::vector<uint32_t>* out) const;

  // From now on there is no triangle holding a -> b (and a rotation through
  // it fails): the region's flood (star_split.cpp) stops at the cut so.
  void forgetEdge(uint32_t a, uint32_t b) {
    if (dense_used_) {
      dense_[a << dense_shift_ | b] = 0;  // the stamp 0 is never a build's
      return;
    }
    const uint32_t e = findHashed(a, b);
    if (e != kNone) edge_triangle_[e] = kNoTriangle;
  }

  // Builds the link of v in `mesh` (its incidence lists), reusing storage.
  void build(const TetComplex& mesh, uint32_t v);

 private:
  static constexpr uint32_t kNone = UINT32_MAX;
  // Links of at most kDense vertices and kDenseFaces triangles use dense_
  // (a sphere on 128 vertices has 252 triangles), rows of 2^dense_shift_
  // entries: 64 for a link of at most 62 triangles (at most 64 vertices),
  // 128 above. One width for all made the CT crop's links (all below 64
  // vertices) 5 % slower at 128, the hand's (some above) 4 % slower at 64,
  // where their links went to the hashed table (pt_decode_bench).
  static constexpr uint32_t kDense = 128;
  static constexpr uint32_t kDenseFaces = 256;
  // A dense entry: the build's 16-bit stamp, the triangle, the third vertex.
  static uint32_t denseEntry(uint32_t stamp, uint32_t f, uint32_t third) { return stamp << 16 | f << 8 | third; }
  // The entry of the directed edge a -> b, or kNone.
  uint32_t find(uint32_t a, uint32_t b) const {
    if (dense_used_) {
      const uint32_t e = dense_[a << dense_shift_ | b];
      return e >> 16 == edge_stamp_ ? e : kNone;
    }
    return findHashed(a, b);
  }
  // Open addressing over the directed edges a -> b, keyed a * 2^32 + b.
  uint32_t findHashed(uint32_t a, uint32_t b) const {
    const uint64_t key = (uint64_t{a} << 32) | b;
    for (uint32_t e = slotOf(key);; e = (e + 1) & mask_) {
      if (edge_key_[e] == key) return e;
      if (edge_key_[e] == kEmpty) return kNone;
    }
  }
  uint32_t slotOf(uint64_t key) const {
    return static_cast<uint32_t>((key * 0x9E3779B97F4A7C15ull) >> shift_) & mask_;
  }
  // The vertex after b in the triangle holding a -> b: next(a, b) of 7.6.1.
  uint32_t thirdOf(uint32_t e) const { return dense_used_ ? e & 0xFF : edge_third_[e]; }
  uint32_t triangleOf(uint32_t e) const { return dense_used_ ? (e >> 8) & 0xFF : edge_triangle_[e]; }
  void insertHashed(uint32_t a, uint32_t b, uint32_t third, uint32_t f);
  void buildHashed();

  static constexpr uint64_t kEmpty = UINT64_MAX;
  std::vector<uint64_t> edge_key_;
  std::vector<uint32_t> edge_triangle_;
  std::vector<uint32_t> edge_third_;
  uint32_t mask_ = 0;
  int shift_ = 60;  // 64 - log2(capacity), set by build()
  bool dense_used_ = false;
  std::vector<uint32_t> dense_;  // per a << dense_shift_ | b: denseEntry() when a -> b is an edge of this build
  uint32_t dense_shift_ = 6;
  uint32_t edge_stamp_ = 0;      // 16 bits: dense_ is cleared when it wraps
  // Scratch of build(): per vertex number, the stamp of the last build that
  // met it (high 32 bits) and its local index there.
  std::vector<uint64_t> tag_of_;
  std::vector<uint32_t> gathered_;  // the link's vertices in the order first met
  uint32_t stamp_ = 0;
};

}  // namespace mrsv
