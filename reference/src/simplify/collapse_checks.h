// The consistency tests every half-edge collapse passes before it is made
// (spec 6.9; paper section 6.2 and Table 1), split by what they look at:
// the boundary rules need only flags, the link condition the two fans'
// connectivity, the geometric tests the positions.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "simplify/edge_topology.h"
#include "simplify/vec3.h"

namespace mrsv::simplify {

// Table 1 of the paper with the half-edge refinement. Case 1 (interior edge,
// interior endpoints) and case 5 (boundary edge) are allowed. Of cases 2 and 3
// (an interior edge with one boundary endpoint) only the direction that
// removes the interior vertex is allowed: the boundary stays as it was. A
// boundary vertex leaves only along a boundary edge; case 4 (interior edge,
// both endpoints on the boundary) is never collapsed, it would pinch the
// surface. h is either half-edge of the edge.
inline bool boundaryRuleAllows(const EdgeTopology& topo, uint32_t removed, uint32_t h) {
  if (topo.edgeOnBoundary(h)) return true;
  return !topo.onBoundary(removed);
}

// Per-vertex marks reused across calls, so a check never allocates.
class VertexMarks {
 public:
  void resize(size_t n) { mark_.assign(n, 0); }
  // Starts a new generation; everything marked before is unmarked.
  void clear() {
    if (++stamp_ == 0) {
      std::fill(mark_.begin(), mark_.end(), 0);
      stamp_ = 1;
    }
  }
  void set(uint32_t v) { mark_[v] = stamp_; }
  bool test(uint32_t v) const { return mark_[v] == stamp_; }

 private:
  std::vector<uint32_t> mark_;
  uint32_t stamp_ = 0;
};

// The link condition (Dey et al.; Hoppe's "legal move" test): the common
// neighbours of the endpoints are exactly the apexes of the edge's one or two
// triangles, with the boundary treated as one extra vertex joined to every
// boundary vertex. It keeps the topology, and with it manifoldness and
// orientation. Also refused: the tetrahedron case (both endpoints interior of
// valence 3, which would leave two copies of one triangle) and a lone
// triangle whose three edges are all on the boundary.
bool linkConditionHolds(const EdgeTopology& topo, uint32_t removed, uint32_t kept, uint32_t h,
                        VertexMarks* marks);

struct GeometryLimits {
  // A triangle whose normal turns by more than acos(min_normal_cos) refuses
  // the collapse (0: 90 degrees).
  double min_normal_cos = 0.0;
  // Shape quality 4 sqrt(3) area / (sum of squared edge lengths), 1 for an
  // equilateral triangle: a new triangle below this (and below the triangle it
  // replaces) is degenerate.
  double min_quality = 1e-3;
};

// No triangle that survives the collapse flips or degenerates when `removed`
// goes to `kept` and `kept` goes to `new_position`. When kept_moves is false
// only the fan of `removed` changes shape.
bool geometryAllows(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t removed,
                    uint32_t kept, const Vec3& new_position, bool kept_moves,
                    const GeometryLimits& limits);

}  // namespace mrsv::simplify
