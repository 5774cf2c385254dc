// Volume and boundary surface of a tet mesh.
#include <limits>

#include "metrics/compensated_sum.h"
#include "metrics/tet_faces.h"
#include "metrics/tet_geometry.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {

double tetMeshVolume(const TetMesh& mesh) {
  CompensatedSum sum;
  for (const auto& t : mesh.tets)
    sum.add(signedTetVolume(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]],
                            mesh.positions[t[3]]));
  return sum.value();
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
