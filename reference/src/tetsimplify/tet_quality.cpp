// Dihedral angles (tet_simplify.h): the shape measure of --min-dihedral and of
// the per-level quality report.
#include <algorithm>
#include <cmath>

#include "simplify/vec3.h"
#include "tetsimplify/tet_simplify.h"

namespace mrsv {

using simplify::cross;
using simplify::dot;
using simplify::sub;
using simplify::Vec3;

double minDihedralDegrees(const std::array<int32_t, 3>& a, const std::array<int32_t, 3>& b,
                          const std::array<int32_t, 3>& c, const std::array<int32_t, 3>& d) {
  const Vec3 p[4] = {{double(a[0]), double(a[1]), double(a[2])},
                     {double(b[0]), double(b[1]), double(b[2])},
                     {double(c[0]), double(c[1]), double(c[2])},
                     {double(d[0]), double(d[1]), double(d[2])}};
  // Outward normals of the faces opposite each corner; the dihedral angle at
  // the edge two faces share is pi minus the angle between their normals.
  constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};
  Vec3 n[4];
  for (int f = 0; f < 4; ++f) {
    n[f] = cross(sub(p[kFace[f][1]], p[kFace[f][0]]), sub(p[kFace[f][2]], p[kFace[f][0]]));
    const double len = std::sqrt(dot(n[f], n[f]));
    if (len == 0.0) return 0.0;
    for (double& x : n[f]) x /= len;
  }
  double largest_cos = -1.0;
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) largest_cos = std::max(largest_cos, -dot(n[i], n[j]));
  }
  return std::acos(std::clamp(largest_cos, -1.0, 1.0)) * (180.0 / M_PI);
}

DihedralStats dihedralStats(const QuantizedTetMesh& mesh) {
  DihedralStats stats;
  if (mesh.tets.empty()) return stats;
  stats.worst = 180.0;
  double sum = 0.0;
  for (const auto& t : mesh.tets) {
    const double m =
        minDihedralDegrees(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]], mesh.positions[t[3]]);
    stats.worst = std::min(stats.worst, m);
    sum += m;
  }
  stats.mean_minimum = sum / double(mesh.tets.size());
  return stats;
}

}  // namespace mrsv
