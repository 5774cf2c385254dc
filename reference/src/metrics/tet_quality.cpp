// Quality figures of a tet mesh: orientation (exact), flatness, dihedral
// angles, plus the manifold and self-intersection checks.
#include <algorithm>
#include <cmath>

#include "metrics/tet_faces.h"
#include "metrics/tet_predicates.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

Point3 sub(const Point3& a, const Point3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const Point3& a, const Point3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

// The smallest and largest dihedral angle of a tet, in degrees. The angle at
// the edge shared by faces i and j is pi minus the angle between their
// outward normals; atan2 keeps it accurate near 0 and 180 (acos would not).
// The normals of an inverted tet all point inward, which gives the same angles.
void dihedralRange(const Point3 (&x)[4], double* lo, double* hi) {
  Point3 n[4];
  for (int f = 0; f < 4; ++f) {
    const Point3& a = x[kOutwardFace[f][0]];
    n[f] = cross(sub(x[kOutwardFace[f][1]], a), sub(x[kOutwardFace[f][2]], a));
  }
  *lo = 180.0;
  *hi = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) {
      const Point3 c = cross(n[i], n[j]);
      const double angle = std::atan2(std::sqrt(dot(c, c)), -dot(n[i], n[j])) * kDegrees;
      *lo = std::min(*lo, angle);
      *hi = std::max(*hi, angle);
    }
}

}  // namespace

TetQuality measureTetQuality(const TetMesh& mesh, const TetQualityOptions& options) {
  TetQuality q;
  q.tets = mesh.tets.size();
  q.vertices = mesh.positions.size();
  double sum_min = 0.0;
  q.min_dihedral_worst = q.tets ? 180.0 : 0.0;
  for (const auto& tet : mesh.tets) {
    const Point3 x[4] = {mesh.positions[tet[0]], mesh.positions[tet[1]], mesh.positions[tet[2]],
                         mesh.positions[tet[3]]};
    const int s = exactOrientation(x[0], x[1], x[2], x[3]);
    double lo = 0.0, hi = 180.0;
    if (s < 0) {
      ++q.inverted;
    } else {
      // 6 |V| against the longest edge cubed: a tet of rounding noise is as
      // useless as an exactly flat one.
      double longest2 = 0.0;
      for (int i = 0; i < 4; ++i)
        for (int j = i + 1; j < 4; ++j) {
          const Point3 e = sub(x[j], x[i]);
          longest2 = std::max(longest2, dot(e, e));
        }
      const double six_volume =
          std::fabs(dot(sub(x[1], x[0]), cross(sub(x[2], x[0]), sub(x[3], x[0]))));
      if (s == 0 || !(six_volume > 1e-12 * longest2 * std::sqrt(longest2))) ++q.degenerate;
    }
    dihedralRange(x, &lo, &hi);
    if (!std::isfinite(lo)) lo = 0.0;  // a zero-area face
    if (!std::isfinite(hi)) hi = 180.0;
    sum_min += lo;
    q.min_dihedral_worst = std::min(q.min_dihedral_worst, lo);
    q.max_dihedral_worst = std::max(q.max_dihedral_worst, hi);
  }
  q.min_dihedral_mean = q.tets ? sum_min / static_cast<double>(q.tets) : 0.0;
  q.volume = tetMeshVolume(mesh);
  q.manifold = checkTetManifold(mesh);
  const TriangleMesh boundary = tetBoundary(mesh);
  q.boundary_faces = boundary.triangles.size();
  if (options.self_intersections)
    q.boundary_self_intersections = static_cast<int64_t>(countBoundarySelfIntersections(boundary));
  return q;
}

}  // namespace mrsv
