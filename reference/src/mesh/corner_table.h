// Triangle connectivity as a corner table, with the vertex split and its
// inverse, the edge collapse, exactly as spec 6.6 defines them.
//
// Face f owns corners 3f, 3f+1, 3f+2 in counter-clockwise order; corner c
// sits at vertex V[c] and faces the edge from next(c) to prev(c); O[c] is the
// corner across that edge in the neighbouring face, or kNone on the boundary.
// Every vertex keeps one of its corners in VC; for a boundary vertex it is the
// first corner of its fan (spec 6.6.1), the one whose face has the vertex's
// outgoing boundary edge, so O[prev(VC[v])] == kNone exactly on the boundary.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace mrsv {

class CornerTable {
 public:
  static constexpr uint32_t kNone = 0xFFFFFFFFu;

  static uint32_t next(uint32_t c) { return c % 3 == 2 ? c - 2 : c + 1; }
  static uint32_t prev(uint32_t c) { return c % 3 == 0 ? c + 2 : c - 1; }

  // Builds the table of an oriented 2-manifold, possibly with boundary, in
  // which every vertex is used. Returns "" or the rule the triangles break.
  std::string build(uint32_t vertex_count, const std::vector<std::array<uint32_t, 3>>& triangles);

  // Room for this many vertices and triangles without reallocating (splits
  // only ever append); a hint, the table still grows past it.
  void reserve(size_t vertices, size_t triangles) {
    vertex_corner_.reserve(vertices);
    corners_.reserve(3 * triangles);
  }

  uint32_t vertexCount() const { return static_cast<uint32_t>(vertex_corner_.size()); }
  uint32_t triangleCount() const { return static_cast<uint32_t>(corners_.size() / 3); }
  uint32_t vertexOf(uint32_t corner) const { return V(corner); }
  bool isBoundary(uint32_t v) const { return O(prev(vertex_corner_[v])) == kNone; }

  // spec 6.6.1 the ring of v: its neighbours in counter-clockwise order and
  // the corner of v in each face F_i = (v, w_i, w_i+1). An interior ring is
  // rotated so that w_0 is the neighbour with the smallest index; a boundary
  // fan starts at the neighbour across v's outgoing boundary edge and has one
  // more neighbour than faces.
  struct Ring {
    bool boundary = false;
    std::vector<uint32_t> neighbours;
    std::vector<uint32_t> corners;
  };
  void ring(uint32_t v, Ring* out) const;
  // A hint that ring(v) comes soon: starts loading the face it begins with.
  void prefetchRing(uint32_t v) const { __builtin_prefetch(&corners_[vertex_corner_[v]]); }

  // What a split added, so that it can be undone.
  struct SplitShape {
    bool has_g1 = false;  // face (vs, w_a, vt) was added
    bool has_g2 = false;  // face (vs, vt, w_b) was added
  };

  // spec 6.6.2 vertex split of vs, whose ring is `ring` (as ring() gave it),
  // at ring positions a and b with the new faces of `shape` (both for an
  // interior vs), which the caller has checked (splitPositionsValid).
  // Adds vertex vertexCount() and one or two faces.
  void split(uint32_t vs, const Ring& ring, uint32_t a, uint32_t b, SplitShape shape);

  // Undoes the last split (whose new vertex is the last vertex).
  void collapseLast(uint32_t vs, SplitShape shape);

  // The faces as vertex triples, corners in stored order.
  std::vector<std::array<uint32_t, 3>> triangles() const;

  // Full consistency check (tests): opposites symmetric and across equal
  // edges, every vertex one fan, VC invariants. Returns "" or the problem.
  std::string validate() const;

 private:
  void link(uint32_t a, uint32_t b) {
    if (a != kNone) O(a) = b;
    if (b != kNone) O(b) = a;
  }
  // Points VC[v] at the start of v's fan, walking clockwise from `corner`.
  void resetVertexCorner(uint32_t v, uint32_t corner);

  // V[c] and O[c] of a corner side by side: walking a ring reads both for
  // each face, so one cache line, not two, has to come in per face.
  struct Corner {
    uint32_t vertex = 0;           // V
    uint32_t opposite = kNone;     // O
  };
  uint32_t& V(uint32_t c) { return corners_[c].vertex; }
  uint32_t V(uint32_t c) const { return corners_[c].vertex; }
  uint32_t& O(uint32_t c) { return corners_[c].opposite; }
  uint32_t O(uint32_t c) const { return corners_[c].opposite; }

  std::vector<Corner> corners_;
  std::vector<uint32_t> vertex_corner_;  // VC
};

// spec 6.6.2: are ring positions a and b a valid split of a ring of this shape?
bool splitPositionsValid(bool boundary, uint32_t neighbours, uint32_t a, uint32_t b,
                         CornerTable::SplitShape shape);

}  // namespace mrsv
