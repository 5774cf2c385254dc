// Replaying collapses on a QuantizedTetMesh (tet_simplify.h): vertex stars
// as plain lists, since this runs once per level, not once per collapse.
#include <algorithm>

#include "tetsimplify/tet_simplify.h"

namespace mrsv {

void applyTetCollapses(const QuantizedTetMesh& mesh, const TetSimplifyResult& result, uint64_t collapses,
                       QuantizedTetMesh* out, std::vector<uint32_t>* vertex_map) {
  const uint32_t nv = static_cast<uint32_t>(mesh.positions.size());
  std::vector<std::array<uint32_t, 4>> tets = mesh.tets;
  std::vector<uint8_t> alive(tets.size(), 1);
  std::vector<std::vector<uint32_t>> star(nv);
  for (uint32_t t = 0; t < tets.size(); ++t) {
    for (uint32_t v : tets[t]) star[v].push_back(t);
  }
  uint64_t done = 0;
  for (const auto& batch : result.batches) {
    for (const TetCollapse& c : batch) {
      if (done++ >= collapses) break;
      for (uint32_t t : star[c.vt]) {
        if (!alive[t]) continue;
        auto& v = tets[t];
        if (std::find(v.begin(), v.end(), c.vs) != v.end()) {
          alive[t] = 0;
          continue;
        }
        *std::find(v.begin(), v.end(), c.vt) = c.vs;
        star[c.vs].push_back(t);
      }
      star[c.vt].clear();
    }
  }
  std::vector<uint32_t> map(nv, ~0u);
  out->tets.clear();
  for (uint32_t t = 0; t < tets.size(); ++t) {
    if (!alive[t]) continue;
    for (uint32_t v : tets[t]) map[v] = 0;
  }
  uint32_t next = 0;
  for (uint32_t v = 0; v < nv; ++v) {
    if (map[v] == 0) map[v] = next++;
  }
  out->positions.assign(next, {0, 0, 0});
  out->fields.assign(mesh.fields.size(), std::vector<double>(next));
  for (uint32_t v = 0; v < nv; ++v) {
    if (map[v] == ~0u) continue;
    out->positions[map[v]] = mesh.positions[v];
    for (size_t f = 0; f < mesh.fields.size(); ++f) out->fields[f][map[v]] = mesh.fields[f][v];
  }
  for (uint32_t t = 0; t < tets.size(); ++t) {
    if (alive[t]) out->tets.push_back({map[tets[t][0]], map[tets[t][1]], map[tets[t][2]], map[tets[t][3]]});
  }
  if (vertex_map) *vertex_map = std::move(map);
}

}  // namespace mrsv
