// Volume and boundary surface of a tet mesh.
#include <cmath>
#include <limits>

#include "metrics/tet_faces.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

double signedVolume(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return (u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
          u[2] * (v[0] * w[1] - v[1] * w[0])) /
         6.0;
}

}  // namespace

double tetMeshVolume(const TetMesh& mesh) {
  // Neumaier's compensated sum: a few hundred thousand small volumes.
  double sum = 0.0, carry = 0.0;
  for (const auto& t : mesh.tets) {
    const double x = signedVolume(mesh.positions[t[0]], mesh.positions[t[1]],
                                  mesh.positions[t[2]], mesh.positions[t[3]]);
    const double s = sum + x;
    carry += std::abs(sum) >= std::abs(x) ? (sum - s) + x : (x - s) + sum;
    sum = s;
  }
  return sum + carry;
}

TriangleMesh tetBoundary(const TetMesh& mesh, std::vector<uint32_t>* tet_vertex) {
  const std::vector<TetFaceUse> uses = sortedTetFaces(mesh);
  TriangleMesh out;
  // Faces in the order of their keys (deterministic), each face its
  // tet's outward order.
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 1) out.triangles.push_back(outwardFace(mesh.tets[uses[i].tet], uses[i].face));
    i = j;
  }
  constexpr uint32_t kUnused = std::numeric_limits<uint32_t>::max();
  std::vector<uint32_t> renumber(mesh.positions.size(), kUnused);
  for (const auto& tri : out.triangles)
    for (uint32_t v : tri) renumber[v] = 0;
  if (tet_vertex) tet_vertex->clear();
  uint32_t next = 0;
  for (size_t v = 0; v < renumber.size(); ++v) {
    if (renumber[v] == kUnused) continue;
    renumber[v] = next++;
    out.positions.push_back(mesh.positions[v]);
    if (tet_vertex) tet_vertex->push_back(static_cast<uint32_t>(v));
  }
  for (auto& tri : out.triangles)
    for (uint32_t& v : tri) v = renumber[v];
  return out;
}

}  // namespace mrsv
