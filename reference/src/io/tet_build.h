// Shared by the grid and PLOT3D tetrahedralizations: tets collected with the
// orientation rule of D38 applied as they come, and vertices no tet uses
// dropped at the end (cells left out leave such vertices behind).
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <utility>
#include <vector>

#include "mrsv/tet_formats.h"

namespace mrsv::tet_build {

// Orders the template tets (corner numbers: bit 0 +i, bit 1 +j, bit 2 +k)
// positively on the unit cube, so a right-handed cell gives positive tets
// and only distorted or left-handed cells need a flip.
inline void orientTemplate(std::array<int, 4>* tets, size_t count) {
  auto corner = [](int c) {
    return std::array<double, 3>{double(c & 1), double((c >> 1) & 1), double((c >> 2) & 1)};
  };
  for (size_t t = 0; t < count; ++t)
    if (orient3dSign(corner(tets[t][0]), corner(tets[t][1]), corner(tets[t][2]), corner(tets[t][3])) < 0)
      std::swap(tets[t][2], tets[t][3]);
}

struct Builder {
  std::vector<std::array<double, 3>> positions;
  std::vector<ScalarField> fields;
  std::vector<std::array<uint32_t, 4>> tets;
  uint64_t flipped = 0;
  uint64_t collapsed = 0;           // tets dropped: two corners at one point
  std::vector<uint32_t> canonical;  // after weld(): each vertex's first copy

  Builder(uint64_t vertices, size_t field_count) : positions(vertices), fields(field_count) {
    for (ScalarField& f : fields) f.values.resize(vertices);
  }
  void reserveTets(uint64_t n) { tets.reserve(n); }

  // Maps every vertex to the first (lowest-numbered) vertex at exactly its
  // position, so tets of cells with a collapsed edge or at a grid seam share
  // vertices; returns how many vertices were merged.
  uint64_t weld() {
    std::vector<uint32_t> order(positions.size());
    std::iota(order.begin(), order.end(), 0u);
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
      return positions[a] != positions[b] ? positions[a] < positions[b] : a < b;
    });
    canonical.resize(positions.size());
    uint64_t merged = 0;
    for (size_t i = 0; i < order.size(); ++i) {
      bool same = i > 0 && positions[order[i]] == positions[order[i - 1]];
      canonical[order[i]] = same ? canonical[order[i - 1]] : order[i];
      merged += same;
    }
    return merged;
  }

  // Adds `tet` (through the weld map, if any), swapping its last two vertices
  // when negatively oriented. A tet with two corners at one vertex is dropped
  // and counted; false (nothing added) when four distinct vertices are coplanar.
  bool addTet(std::array<uint32_t, 4> tet) {
    if (!canonical.empty()) {
      for (uint32_t& v : tet) v = canonical[v];
      if (tet[0] == tet[1] || tet[0] == tet[2] || tet[0] == tet[3] || tet[1] == tet[2] ||
          tet[1] == tet[3] || tet[2] == tet[3]) {
        ++collapsed;
        return true;
      }
    }
    int sign = orient3dSign(positions[tet[0]], positions[tet[1]], positions[tet[2]], positions[tet[3]]);
    if (sign == 0) return false;
    if (sign < 0) {
      std::swap(tet[2], tet[3]);
      ++flipped;
    }
    tets.push_back(tet);
    return true;
  }

  // Appends a vertex (not welded to any other) and returns its number.
  uint32_t addVertex(const std::array<double, 3>& position, const std::vector<double>& values) {
    const auto v = static_cast<uint32_t>(positions.size());
    positions.push_back(position);
    for (size_t f = 0; f < fields.size(); ++f) fields[f].values.push_back(values[f]);
    if (!canonical.empty()) canonical.push_back(v);
    return v;
  }

  // Adds the tets of one cell (through the weld map, if any) when, leaving
  // out those with two corners at one vertex, all are positive, or all
  // negative (then each is flipped, as a left-handed cell needs). False, and
  // nothing added, when one is flat or their orientations differ: the cut
  // does not fit the cell, and its tets would overlap.
  bool addCell(const std::array<uint32_t, 4>* cell_tets, size_t count) {
    std::array<uint32_t, 4> kept[16];
    size_t n = 0;
    int cell_sign = 0;
    uint64_t dropped = 0;
    for (size_t t = 0; t < count; ++t) {
      std::array<uint32_t, 4> tet = cell_tets[t];
      if (!canonical.empty())
        for (uint32_t& v : tet) v = canonical[v];
      if (tet[0] == tet[1] || tet[0] == tet[2] || tet[0] == tet[3] || tet[1] == tet[2] ||
          tet[1] == tet[3] || tet[2] == tet[3]) {
        ++dropped;
        continue;
      }
      int sign =
          orient3dSign(positions[tet[0]], positions[tet[1]], positions[tet[2]], positions[tet[3]]);
      if (sign == 0 || (cell_sign != 0 && sign != cell_sign) || n == 16) return false;
      cell_sign = sign;
      kept[n++] = tet;
    }
    for (size_t t = 0; t < n; ++t) {
      if (cell_sign < 0) std::swap(kept[t][2], kept[t][3]);
      tets.push_back(kept[t]);
    }
    if (cell_sign < 0) flipped += n;
    collapsed += dropped;
    return true;
  }

  // Moves the result into `mesh`, dropping vertices no tet uses.
  void finish(TetMesh* mesh) {
    std::vector<uint32_t> remap(positions.size(), UINT32_MAX);
    for (const auto& t : tets)
      for (uint32_t v : t) remap[v] = 0;
    uint32_t next = 0;
    for (uint32_t& r : remap)
      if (r == 0) r = next++;
    if (next != positions.size()) {
      for (size_t v = 0; v < positions.size(); ++v)
        if (remap[v] != UINT32_MAX) {
          positions[remap[v]] = positions[v];
          for (ScalarField& f : fields) f.values[remap[v]] = f.values[v];
        }
      positions.resize(next);
      for (ScalarField& f : fields) f.values.resize(next);
      for (auto& t : tets)
        for (uint32_t& v : t) v = remap[v];
    }
    mesh->positions = std::move(positions);
    mesh->tets = std::move(tets);
    mesh->fields = std::move(fields);
  }
};

}  // namespace mrsv::tet_build
