#include "simplify/collapse_costs.h"

#include <cmath>

namespace mrsv::simplify {

namespace {

// Below this det / (trace / 3)^3 the minimiser of a quadric is too unstable
// to use: it means one principal curvature direction is pinned down less than
// about 1e-3 as firmly as the mean.
constexpr double kConditionLimit = 1e-6;

}  // namespace

bool Quadric::constrainedMinimizer(const Vec3& g, double offset, Vec3* out) const {
  // With A the 3x3 part and b = (q3, q6, q8), the free minimiser is
  // x0 = -A^-1 b; on the plane g . x = offset the minimiser is
  // x0 + t A^-1 g with t = (offset - g . x0) / (g . A^-1 g) (Lagrange).
  const double c00 = q[4] * q[7] - q[5] * q[5];
  const double c01 = q[2] * q[5] - q[1] * q[7];
  const double c02 = q[1] * q[5] - q[2] * q[4];
  const double c11 = q[0] * q[7] - q[2] * q[2];
  const double c12 = q[1] * q[2] - q[0] * q[5];
  const double c22 = q[0] * q[4] - q[1] * q[1];
  const double det = q[0] * c00 + q[1] * c01 + q[2] * c02;
  const double mean = (q[0] + q[4] + q[7]) / 3.0;
  if (!(mean > 0.0) || !(det > kConditionLimit * mean * mean * mean)) return false;
  const double inv = 1.0 / det;
  const Vec3 x0 = {-inv * (c00 * q[3] + c01 * q[6] + c02 * q[8]),
                   -inv * (c01 * q[3] + c11 * q[6] + c12 * q[8]),
                   -inv * (c02 * q[3] + c12 * q[6] + c22 * q[8])};
  const Vec3 y = {inv * (c00 * g[0] + c01 * g[1] + c02 * g[2]), inv * (c01 * g[0] + c11 * g[1] + c12 * g[2]),
                  inv * (c02 * g[0] + c12 * g[1] + c22 * g[2])};
  const double gy = dot(g, y);
  // A is positive definite here, so g . A^-1 g > 0 unless g is (numerically)
  // zero: fans that enclose no volume either way leave x0 as it is.
  const double t = gy > 0.0 ? (offset - dot(g, x0)) / gy : 0.0;
  *out = {x0[0] + t * y[0], x0[1] + t * y[1], x0[2] + t * y[2]};
  return std::isfinite((*out)[0]) && std::isfinite((*out)[1]) && std::isfinite((*out)[2]);
}

Vec3 Quadric::segmentMinimizer(const Vec3& a, const Vec3& b) const {
  // e(a + t (b - a)) = alpha t^2 + beta t + f0, from its values at 0, 1/2, 1.
  const double f0 = evaluate(a);
  const double f1 = evaluate(b);
  const Vec3 mid = {0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1]), 0.5 * (a[2] + b[2])};
  const double fh = evaluate(mid);
  const double alpha = 2.0 * (f0 + f1 - 2.0 * fh);
  const double beta = 4.0 * fh - 3.0 * f0 - f1;
  if (!(alpha > 0.0)) return f0 <= f1 ? a : b;
  const double t = std::fmin(1.0, std::fmax(0.0, -beta / (2.0 * alpha)));
  if (t == 0.0) return a;
  if (t == 1.0) return b;
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

TrianglePlane trianglePlane(const Vec3& a, const Vec3& b, const Vec3& c) {
  TrianglePlane t;
  t.n = cross(sub(b, a), sub(c, a));
  t.offset = dot(t.n, a);
  const double twice_area = length(t.n);
  t.quadric_scale = twice_area > 0.0 ? 0.5 / twice_area : 0.0;
  return t;
}

void vertexQuadric(const EdgeTopology& topo, const std::vector<Vec3>& positions,
                   const std::vector<TrianglePlane>& planes, uint32_t v, double boundary_weight,
                   Quadric* quadric, VolumeTerm* volume) {
  // The sums build up in locals and are stored once: accumulating through the
  // pointers made the compiler store all 14 values after every triangle (they
  // might alias the planes), and this runs for every vertex a collapse touches.
  Quadric sum;
  VolumeTerm enclosed;
  const bool boundary = topo.onBoundary(v);
  topo.forEachOutgoing(v, [&](uint32_t h) {
    const TrianglePlane& t = planes[EdgeTopology::triangleOf(h)];
    enclosed.add({t.n, t.offset});
    if (!(t.quadric_scale > 0.0)) return;
    sum.addPlane(t.n, -t.offset, t.quadric_scale);
    if (!boundary) return;
    // The fan's boundary edges: the outgoing one of its first triangle and the
    // incoming one of its last; both are edges of this triangle through v.
    for (uint32_t e : {h, EdgeTopology::prev(h)}) {
      if (!topo.edgeOnBoundary(e)) continue;
      const Vec3& e0 = positions[topo.vertexOf(e)];
      const Vec3 along = sub(positions[topo.target(e)], e0);
      Vec3 m = cross(along, t.n);
      const double ml = length(m);
      if (!(ml > 0.0)) continue;
      m = {m[0] / ml, m[1] / ml, m[2] / ml};
      sum.addPlane(m, -dot(m, e0), boundary_weight * dot(along, along));
    }
  });
  *quadric = sum;
  *volume = enclosed;
}

Vec3 vertexNormal(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t v) {
  Vec3 sum = {0.0, 0.0, 0.0};
  const Vec3& p = positions[v];
  topo.forEachOutgoing(v, [&](uint32_t h) {
    const Vec3& x = positions[topo.target(h)];
    const Vec3& y = positions[topo.vertexOf(EdgeTopology::prev(h))];
    const Vec3 n = cross(sub(x, p), sub(y, p));
    sum = {sum[0] + n[0], sum[1] + n[1], sum[2] + n[2]};
  });
  const double l = length(sum);
  if (!(l > 0.0)) return {0.0, 0.0, 0.0};
  return {sum[0] / l, sum[1] / l, sum[2] / l};
}

namespace {

// E(T) = sum over the three edges of (l_e - m)^2, m the mean edge length.
inline double equilateralEnergy(const Vec3& a, const Vec3& b, const Vec3& c, double unit) {
  const double l0 = length(sub(b, a)) * unit;
  const double l1 = length(sub(c, b)) * unit;
  const double l2 = length(sub(a, c)) * unit;
  const double m = (l0 + l1 + l2) / 3.0;
  return (l0 - m) * (l0 - m) + (l1 - m) * (l1 - m) + (l2 - m) * (l2 - m);
}

// Sum of E(after) - E(before) over the triangles of v's fan without `other`,
// v going to `to`.
double fanEquilateralChange(const EdgeTopology& topo, const std::vector<Vec3>& positions,
                            uint32_t v, uint32_t other, const Vec3& to, double unit) {
  double change = 0.0;
  const Vec3& from = positions[v];
  topo.forEachOutgoing(v, [&](uint32_t h) {
    const uint32_t x = topo.target(h);
    const uint32_t y = topo.vertexOf(EdgeTopology::prev(h));
    if (x == other || y == other) return;
    change += equilateralEnergy(to, positions[x], positions[y], unit) -
              equilateralEnergy(from, positions[x], positions[y], unit);
  });
  return change;
}

}  // namespace

double paperEnergy(const EdgeTopology& topo, const std::vector<Vec3>& positions,
                   const std::vector<Vec3>& normals, uint32_t removed, uint32_t kept,
                   const Vec3& new_position, bool kept_moves, const PaperWeights& weights) {
  const double unit = weights.inverse_length_unit;
  const double l = length(sub(positions[removed], positions[kept])) * unit;
  const double normal = (1.0 - dot(normals[removed], normals[kept])) * l * l;
  double equilateral =
      fanEquilateralChange(topo, positions, removed, kept, new_position, unit);
  if (kept_moves) {
    equilateral += fanEquilateralChange(topo, positions, kept, removed, new_position, unit);
  }
  return weights.normal * normal + weights.edge_length * l + weights.equilateral * equilateral;
}

}  // namespace mrsv::simplify
