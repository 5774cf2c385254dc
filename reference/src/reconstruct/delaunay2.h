// An incremental 2-D Delaunay triangulation of grid points inside a
// rectangle whose four corners are vertices (spec 8.4). Points are added one
// at a time (Lawson: split the triangle or edge that holds the point, then
// flip edges that fail the perturbed in-circle test), so the triangulation is
// always the unique perturbed Delaunay triangulation of the points added,
// each with its rank (spec 8.3).
// Triangle slots are never freed: a split adds one or two, a flip reuses both.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "reconstruct/exact_predicates2.h"

namespace mrsv::reconstruct {

class Delaunay2 {
 public:
  static constexpr uint32_t kNone = UINT32_MAX;

  // The rectangle [0, max_x] x [0, max_y] (both at least 1) as two triangles;
  // its corners (0, 0), (max_x, 0), (max_x, max_y), (0, max_y) have the ranks
  // `corner_ranks` (by default 0 to 3).
  Delaunay2(int32_t max_x, int32_t max_y, const uint64_t* corner_ranks = nullptr);

  // A triangle holding p (inside or on its border), walking from `hint`.
  uint32_t locate(Point2 p, uint32_t hint) const;

  // Adds p with `rank` (distinct from every other vertex's), which must lie
  // in triangle `t` (inside or on an edge) and not be a vertex. The slots of
  // every triangle made or changed are appended to `touched`, when given
  // (possibly more than once); they are the triangles around the new vertex,
  // t among them. Returns the new vertex's number.
  uint32_t insert(Point2 p, uint64_t rank, uint32_t t, std::vector<uint32_t>* touched = nullptr);

  // The triangles around vertex v, one way and the other: the neighbour of
  // t (which has corner v) across its edge from v to the next corner, or
  // across the edge from the previous corner to v; kNone on the border.
  uint32_t nextAround(uint32_t t, uint32_t v) const {
    const auto& c = tri_[t].v;
    return tri_[t].n[c[0] == v ? 2 : c[1] == v ? 0 : 1];
  }
  uint32_t previousAround(uint32_t t, uint32_t v) const {
    const auto& c = tri_[t].v;
    return tri_[t].n[c[0] == v ? 1 : c[1] == v ? 2 : 0];
  }

  size_t vertexCount() const { return points_.size(); }
  size_t triangleCount() const { return tri_.size(); }
  Point2 point(uint32_t v) const { return points_[v]; }
  // Counter-clockwise corners; edge i is the one opposite corner i.
  const std::array<uint32_t, 3>& triangle(uint32_t t) const { return tri_[t].v; }
  // The triangle across edge i, or kNone on the rectangle's border.
  const std::array<uint32_t, 3>& neighbours(uint32_t t) const { return tri_[t].n; }

 private:
  // Small and called at every split and flip: defined here to be inlined.
  uint32_t addTriangle() {
    tri_.push_back({{0, 0, 0}, {kNone, kNone, kNone}});
    return static_cast<uint32_t>(tri_.size() - 1);
  }
  void set(uint32_t t, uint32_t a, uint32_t b, uint32_t c, uint32_t na, uint32_t nb, uint32_t nc) {
    tri_[t].v = {a, b, c};
    tri_[t].n = {na, nb, nc};
  }
  // The edge of t across which lies its neighbour u, computed rather than
  // searched (which edge it is cannot be predicted).
  int edgeTo(uint32_t t, uint32_t u) const {
    const auto& n = tri_[t].n;
    return int(n[1] == u) + 2 * int(n[2] == u);
  }
  void replaceNeighbour(uint32_t t, uint32_t from, uint32_t to) {
    if (t == kNone) return;
    tri_[t].n[edgeTo(t, from)] = to;
  }
  // The same for an edge that a flip will test: the corner of t facing it,
  // which the in-circle test reads, starts loading.
  void replaceNeighbourToTest(uint32_t t, uint32_t from, uint32_t to) {
    if (t == kNone) return;
    const int k = edgeTo(t, from);
    tri_[t].n[k] = to;
    __builtin_prefetch(&points_[tri_[t].v[k]]);
  }
  // Flips edges opposite the new vertex until all are locally Delaunay.
  void legalize(std::vector<uint32_t>* touched);

  bool conflict(uint32_t a, uint32_t b, uint32_t c, uint32_t d) const {
    // The ranks are read only for cocircular points, where the perturbation decides.
    const int s = incircle(points_[a], points_[b], points_[c], points_[d]);
    if (s != 0) return s > 0;
    const uint64_t rank[4] = {rankOf(a), rankOf(b), rankOf(c), rankOf(d)};
    return cocircularConflict(points_[a], points_[b], points_[c], points_[d], rank);
  }

  // A vertex's rank without reading ranks_ (a random read of its own) while
  // every rank is the vertex's number, as the greedy insertion gives them.
  uint64_t rankOf(uint32_t v) const { return ranks_are_numbers_ ? v : ranks_[v]; }
  // Starts loading triangle t (kNone: nothing) that a flip will soon read:
  // the flips' reads are random, and issued together they overlap.
  void prefetch(uint32_t t) const {
    if (t != kNone) __builtin_prefetch(&tri_[t]);
  }

  std::vector<Point2> points_;
  std::vector<uint64_t> ranks_;
  bool ranks_are_numbers_ = true;
  // A triangle's corners and neighbours side by side: a split or flip reads both.
  struct Triangle {
    std::array<uint32_t, 3> v;
    std::array<uint32_t, 3> n;
  };
  std::vector<Triangle> tri_;
  std::vector<uint32_t> stack_;  // triangles whose edge 0 (opposite the new vertex) awaits a test
};

}  // namespace mrsv::reconstruct
