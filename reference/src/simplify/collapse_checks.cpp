#include "simplify/collapse_checks.h"

namespace mrsv::simplify {

bool linkConditionHolds(const EdgeTopology& topo, uint32_t removed, uint32_t kept, uint32_t h,
                        VertexMarks* marks) {
  const uint32_t twin = topo.opposite(h);
  const uint32_t apex_h = topo.vertexOf(EdgeTopology::prev(h));
  const uint32_t apex_twin = twin == kNone ? kNone : topo.vertexOf(EdgeTopology::prev(twin));
  if (apex_h == apex_twin) return false;  // two triangles on the same three vertices

  if (twin == kNone) {
    // Boundary edge: the extra boundary vertex is a common neighbour, which
    // the link of the edge allows only through its triangle's apex. Were both
    // other edges of the triangle on the boundary too, the boundary vertex and
    // the apex would span a common link edge (a lone triangle).
    if (topo.edgeOnBoundary(EdgeTopology::next(h)) && topo.edgeOnBoundary(EdgeTopology::prev(h))) {
      return false;
    }
  }

  marks->clear();
  uint32_t valence_removed = 0;
  topo.forEachNeighbour(removed, [&](uint32_t w) {
    marks->set(w);
    ++valence_removed;
  });
  uint32_t common = 0;
  uint32_t valence_kept = 0;
  topo.forEachNeighbour(kept, [&](uint32_t w) {
    common += marks->test(w);
    ++valence_kept;
  });
  const uint32_t expected = twin == kNone ? 1u : 2u;
  if (common != expected) return false;
  if (twin != kNone && valence_removed == 3 && valence_kept == 3 && !topo.onBoundary(removed) &&
      !topo.onBoundary(kept)) {
    return false;  // a tetrahedron: the collapse would leave a doubled triangle
  }
  return true;
}

namespace {

// The triangle (p, x, y) with p moved from `from` to `to`: false if it flips
// or degenerates.
inline bool triangleStaysValid(const Vec3& from, const Vec3& to, const Vec3& x, const Vec3& y,
                               const GeometryLimits& limits) {
  const Vec3 xy = sub(y, x);
  const Vec3 n_old = cross(sub(x, from), sub(y, from));
  const Vec3 ex = sub(x, to);
  const Vec3 ey = sub(y, to);
  const Vec3 n_new = cross(ex, ey);
  const double nn_new = dot(n_new, n_new);
  if (!(nn_new > 0.0)) return false;
  // cos(turn angle) > min_normal_cos, compared without square roots. A
  // zero-area triangle of the input has no orientation to keep.
  const double turn = dot(n_old, n_new);
  const double nn_old = dot(n_old, n_old);
  const double c = limits.min_normal_cos;
  const double bound = c * c * nn_old * nn_new;
  if (nn_old > 0.0) {
    if (c >= 0.0 ? (turn <= 0.0 || turn * turn <= bound) : (turn < 0.0 && turn * turn >= bound)) {
      return false;
    }
  }
  // quality^2 = 48 area^2 / S^2 = 12 |n|^2 / S^2, compared without roots.
  const double s_new = dot(ex, ex) + dot(ey, ey) + dot(xy, xy);
  const double q2_new = 12.0 * nn_new / (s_new * s_new);
  const double min_q2 = limits.min_quality * limits.min_quality;
  if (q2_new < min_q2) {
    const Vec3 fx = sub(x, from);
    const Vec3 fy = sub(y, from);
    const double s_old = dot(fx, fx) + dot(fy, fy) + dot(xy, xy);
    const double q2_old = s_old > 0.0 ? 12.0 * nn_old / (s_old * s_old) : 0.0;
    if (q2_new < q2_old) return false;
  }
  return true;
}

// Checks every triangle of v's fan that does not contain `other`, with v
// moved to `to`.
inline bool fanStaysValid(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t v,
                          uint32_t other, const Vec3& to, const GeometryLimits& limits) {
  const Vec3& from = positions[v];
  bool ok = true;
  const uint32_t start = topo.outgoing(v);
  uint32_t h = start;
  do {
    const uint32_t x = topo.target(h);
    const uint32_t y = topo.vertexOf(EdgeTopology::prev(h));
    if (x != other && y != other &&
        !triangleStaysValid(from, to, positions[x], positions[y], limits)) {
      ok = false;
      break;
    }
    h = topo.rotateCcw(h);
  } while (h != kNone && h != start);
  return ok;
}

}  // namespace

bool geometryAllows(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t removed,
                    uint32_t kept, const Vec3& new_position, bool kept_moves,
                    const GeometryLimits& limits) {
  if (!fanStaysValid(topo, positions, removed, kept, new_position, limits)) return false;
  return !kept_moves || fanStaysValid(topo, positions, kept, removed, new_position, limits);
}

}  // namespace mrsv::simplify
