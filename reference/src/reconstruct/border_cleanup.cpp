// spec: 8.8 the border cleanup after insertion with the border rule.
//
// 9.7's pass, once, over the border zone only. The zone's vertices are few
// (a band one triangle deep along the sides), so the pass runs on the
// sub-mesh of the triangles that touch one of them, not on the whole mesh:
// a removal only ever re-triangulates the star of a zone vertex, and those
// stars (and every star a removal makes of them) are made of such triangles.
// On the whole mesh the pass's set-up (numbering, corner table, compaction)
// made `mrsv mesh --max-error 1` of Big Tujunga (900,000 triangles) take
// 1.9 s instead of 1.2 (D88); what is left here is a few passes over the
// triangles.
#include <algorithm>
#include <array>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "mrsv/terrain_insertion.h"
#include "reconstruct/quadtree_error.h"
#include "reconstruct/quadtree_removal.h"

namespace mrsv {

bool cleanBorderZone(const SampleField& field, const ErrorBound& bound, GridMesh* mesh, uint64_t* removed,
                     std::string* error) {
  if (field.dims() != 2 || mesh->dims != 2 || mesh->size[0] != field.size[0] || mesh->size[1] != field.size[1] ||
      field.size[0] < 2 || field.size[1] < 2) {
    if (error) *error = "the border cleanup takes a 2-D mesh of the field's grid";
    return false;
  }
  if (!bound.set() || bound.den <= 0) {
    if (error) *error = "the border cleanup needs a maximum error";
    return false;
  }
  constexpr uint32_t kNone = 0xFFFFFFFFu;
  const uint32_t w = mesh->size[0], h = mesh->size[1];
  const uint32_t v_count = static_cast<uint32_t>(mesh->points.size());
  // Per vertex: kBorder on the grid's border, kZone an inner vertex of a
  // triangle with a border vertex. Bytes, read three per triangle: the
  // passes over the triangles below are what the cleanup costs on a large
  // mesh (a 1201^2 terrain at 1 m has 2.3 million).
  constexpr uint8_t kBorder = 1, kZone = 2;
  std::vector<uint8_t> kind(v_count, 0);
  for (uint32_t v = 0; v < v_count; ++v) {
    const auto& p = mesh->points[v];
    kind[v] = p[0] == 0 || p[1] == 0 || p[0] + 1 == w || p[1] + 1 == h ? kBorder : 0;
  }
  std::vector<std::array<uint32_t, 4>>& cells = mesh->cells;
  for (const auto& cell : cells)
    if ((kind[cell[0]] | kind[cell[1]] | kind[cell[2]]) & kBorder)
      for (int k = 0; k < 3; ++k)
        if (kind[cell[k]] != kBorder) kind[cell[k]] = kZone;
  // The sub-mesh of the triangles touching the zone, in the grid's frame;
  // the other triangles stay where they are, moved up over the sub-mesh's.
  GridMesh sub;
  sub.dims = 2;
  std::copy(mesh->size, mesh->size + 3, sub.size);
  std::unordered_map<uint32_t, uint32_t> local;
  std::vector<uint32_t> origin;  // the mesh's vertex of each sub-mesh point
  size_t kept_cells = 0;
  for (size_t t = 0; t < cells.size(); ++t) {
    const auto cell = cells[t];
    if (!((kind[cell[0]] | kind[cell[1]] | kind[cell[2]]) & kZone)) {
      cells[kept_cells++] = cell;
      continue;
    }
    std::array<uint32_t, 4> c{0, 0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const auto [it, fresh] = local.try_emplace(cell[k], static_cast<uint32_t>(origin.size()));
      if (fresh) {
        origin.push_back(cell[k]);
        sub.points.push_back(mesh->points[cell[k]]);
        sub.values.push_back(mesh->values[cell[k]]);
      }
      c[k] = it->second;
    }
    sub.cells.push_back(c);
  }
  cells.resize(kept_cells);
  const quadtree::ErrorTest test(field, bound);
  quadtree::RemovalReport report;
  quadtree::removeVertices(test, &sub, quadtree::kBorderCleanup, &report);

  // From here kind[v] says whether v stays: the sub-mesh's vertices only
  // when they survived.
  std::vector<uint32_t> from_sub(sub.points.size());
  std::fill(kind.begin(), kind.end(), 1);
  for (uint32_t v : origin) kind[v] = 0;
  // The pass keeps its survivors in their order: a subsequence of `origin`.
  size_t o = 0;
  for (uint32_t s = 0; s < sub.points.size(); ++s) {
    while (mesh->points[origin[o]] != sub.points[s]) ++o;
    from_sub[s] = origin[o];
    kind[origin[o]] = 1;
  }
  for (const auto& cell : sub.cells) cells.push_back({from_sub[cell[0]], from_sub[cell[1]], from_sub[cell[2]], 0});
  if (report.removed > 0) {
    // The removed vertices leave the point list; the others move up.
    std::vector<uint32_t> number(v_count, kNone);
    uint32_t n = 0;
    for (uint32_t v = 0; v < v_count; ++v) {
      if (!kind[v]) continue;
      number[v] = n;
      mesh->points[n] = mesh->points[v];
      mesh->values[n] = mesh->values[v];
      ++n;
    }
    mesh->points.resize(n);
    mesh->values.resize(n);
    for (auto& cell : cells)
      for (int k = 0; k < 3; ++k) cell[k] = number[cell[k]];
  }
  if (removed) *removed = report.removed;
  return true;
}

}  // namespace mrsv
