// The mutable tet complex (tet_complex.h).
#include "tetsimplify/tet_complex.h"

#include <algorithm>

namespace mrsv::tetsimplify {

namespace {

// The outward face opposite each corner of a positively oriented tet.
constexpr int kFace[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

struct FaceEntry {
  uint32_t x, y;  // the face's other two vertices, x < y
  uint32_t corner;  // 4 t + f
  bool forward;     // whether the outward triple, rotated to start at the smallest vertex, runs x -> y
};

}  // namespace

bool TetComplex::build(const std::vector<IPoint>& positions, const std::vector<std::array<uint32_t, 4>>& tets,
                       std::string* error) {
  positions_ = positions;
  tets_ = tets;
  const uint32_t nv = static_cast<uint32_t>(positions.size());
  const uint32_t nt = static_cast<uint32_t>(tets.size());
  stars_.assign(nv);
  alive_.assign(nt, 1);
  boundary_.assign(nt, 0);
  boundary_vertex_.assign(nv, 0);
  for (const IPoint& p : positions_) {
    for (int32_t x : p) {
      if (x < 0 || x >= (1 << 30)) {
        *error = "vertex " + std::to_string(&p - positions_.data()) + ": coordinate outside [0, 2^30)";
        return false;
      }
    }
  }
  std::vector<uint32_t> star_size(nv, 0);
  for (uint32_t t = nt; t-- > 0;) {
    const auto& v = tets_[t];
    for (int i = 0; i < 4; ++i) {
      if (v[i] >= nv) {
        *error = "tet " + std::to_string(t) + ": vertex index " + std::to_string(v[i]) + " out of range";
        return false;
      }
    }
    if (orient3d(positions_[v[0]], positions_[v[1]], positions_[v[2]], positions_[v[3]]) <= 0) {
      *error = "tet " + std::to_string(t) + ": not positively oriented (orient3d <= 0)";
      return false;
    }
    for (int i = 0; i < 4; ++i) ++star_size[v[i]];
  }
  // Each star in increasing tet order (the order the simplifier's choices
  // among equal costs follow), its block sized once, the blocks in vertex order.
  for (uint32_t v = 0; v < nv; ++v) stars_.reserve(v, star_size[v]);
  for (uint32_t t = 0; t < nt; ++t) {
    for (uint32_t i = 0; i < 4; ++i) stars_.push(tets_[t][i], 4 * t + i);
  }
  live_tets_ = nt;
  live_vertices_ = 0;
  for (uint32_t v = 0; v < nv; ++v) live_vertices_ += !stars_.empty(v);

  // Faces, grouped by their smallest vertex: each is matched within that
  // vertex's star, a short list, so no global sort or hash is needed.
  std::vector<FaceEntry> faces;
  std::vector<std::array<uint32_t, 2>> edges;
  std::vector<uint32_t> parent;
  for (uint32_t m = 0; m < nv; ++m) {
    faces.clear();
    edges.clear();
    uint32_t link_triangles = 0;
    forEachTet(m, [&](uint32_t t, uint32_t corner) {
      const auto& v = tets_[t];
      ++link_triangles;
      const uint32_t o[3] = {v[(corner + 1) & 3], v[(corner + 2) & 3], v[(corner + 3) & 3]};
      edges.push_back({std::min(o[0], o[1]), std::max(o[0], o[1])});
      edges.push_back({std::min(o[1], o[2]), std::max(o[1], o[2])});
      edges.push_back({std::min(o[0], o[2]), std::max(o[0], o[2])});
      for (uint32_t f = 0; f < 4; ++f) {
        if (f == corner) continue;
        uint32_t w[3] = {v[kFace[f][0]], v[kFace[f][1]], v[kFace[f][2]]};
        if (std::min({w[0], w[1], w[2]}) != m) continue;
        while (w[0] != m) std::rotate(w, w + 1, w + 3);
        faces.push_back({std::min(w[1], w[2]), std::max(w[1], w[2]), 4 * t + f, w[1] < w[2]});
      }
    });
    std::sort(faces.begin(), faces.end(),
              [](const FaceEntry& a, const FaceEntry& b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
    for (size_t i = 0; i < faces.size();) {
      size_t j = i + 1;
      while (j < faces.size() && faces[j].x == faces[i].x && faces[j].y == faces[i].y) ++j;
      auto name = [&] {
        return "face (" + std::to_string(m) + ", " + std::to_string(faces[i].x) + ", " + std::to_string(faces[i].y) + ")";
      };
      if (j - i > 2) {
        *error = name() + ": in more than two tets";
        return false;
      }
      if (j - i == 2 && faces[i].forward == faces[i + 1].forward) {
        *error = name() + ": its two tets give it the same orientation";
        return false;
      }
      if (j - i == 1) boundary_[faces[i].corner >> 2] |= uint8_t(1u << (faces[i].corner & 3));
      i = j;
    }
    // The link of m: a sphere (no edge in one triangle, Euler characteristic
    // 2) or a disk (characteristic 1).
    if (link_triangles == 0) continue;
    std::sort(edges.begin(), edges.end());
    uint32_t unique_edges = 0, border_edges = 0;
    for (size_t i = 0; i < edges.size();) {
      size_t j = i + 1;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i > 2) {
        *error = "vertex " + std::to_string(m) + ": its link is not a surface (edge (" +
                 std::to_string(edges[i][0]) + ", " + std::to_string(edges[i][1]) + ") in more than two of its triangles)";
        return false;
      }
      ++unique_edges;
      border_edges += j - i == 1;
      i = j;
    }
    uint32_t link_vertices = 0;
    std::vector<uint32_t>& ends = ring_;
    ends.clear();
    for (const auto& e : edges) {
      ends.push_back(e[0]);
      ends.push_back(e[1]);
    }
    std::sort(ends.begin(), ends.end());
    link_vertices = static_cast<uint32_t>(std::unique(ends.begin(), ends.end()) - ends.begin());
    // Connected (a sphere beside a torus has characteristic 2 too).
    parent.resize(link_vertices);
    for (uint32_t i = 0; i < link_vertices; ++i) parent[i] = i;
    auto find = [&](uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    uint32_t components = link_vertices;
    for (const auto& e : edges) {
      const uint32_t a = find(uint32_t(std::lower_bound(ends.begin(), ends.begin() + link_vertices, e[0]) - ends.begin()));
      const uint32_t b = find(uint32_t(std::lower_bound(ends.begin(), ends.begin() + link_vertices, e[1]) - ends.begin()));
      if (a != b) {
        parent[a] = b;
        --components;
      }
    }
    if (components != 1) {
      *error = "vertex " + std::to_string(m) + ": its link is not connected";
      return false;
    }
    const int64_t euler = int64_t(link_vertices) - unique_edges + link_triangles;
    if (euler != (border_edges ? 1 : 2)) {
      *error = "vertex " + std::to_string(m) + ": its link is neither a sphere nor a disk (Euler characteristic " +
               std::to_string(euler) + ")";
      return false;
    }
    boundary_vertex_[m] = border_edges != 0;
  }
  return true;
}

void TetComplex::collapse(uint32_t vs, uint32_t vt, std::vector<uint32_t>* vanished) {
  // The tets around the edge vanish. Where one had a boundary face opposite
  // vs (vt p q), the face vs p q of its neighbour across from vt becomes
  // boundary; where it had one opposite vt (vs p q), the face vt p q of its
  // neighbour across from vs becomes boundary (and is vs p q afterwards).
  // Both at once would glue nothing to nothing: the link condition excludes it.
  ring_.clear();
  forEachTet(vt, [&](uint32_t t, uint32_t) {
    const auto& v = tets_[t];
    if (v[0] == vs || v[1] == vs || v[2] == vs || v[3] == vs) ring_.push_back(t);
  });
  for (uint32_t t : ring_) {
    const auto& v = tets_[t];
    uint32_t is = 0, it = 0;
    for (uint32_t i = 0; i < 4; ++i) {
      if (v[i] == vs) is = i;
      if (v[i] == vt) it = i;
    }
    const bool opposite_vs = boundary_[t] >> is & 1, opposite_vt = boundary_[t] >> it & 1;
    if (opposite_vs == opposite_vt) continue;
    uint32_t p = kNone, q = kNone;
    for (uint32_t i = 0; i < 4; ++i) {
      if (i != is && i != it) (p == kNone ? p : q) = v[i];
    }
    // The neighbour across the interior face holds its apex (kept or
    // removed vertex), p and q; its face opposite the fourth vertex turns.
    const uint32_t apex = opposite_vs ? vs : vt;
    forEachTet(apex, [&](uint32_t u, uint32_t corner) {
      if (u == t) return;
      const auto& w = tets_[u];
      uint32_t other = kNone;
      int found = 0;
      for (uint32_t i = 0; i < 4; ++i) {
        if (i == corner) continue;
        if (w[i] == p || w[i] == q) {
          ++found;
        } else {
          other = i;
        }
      }
      if (found == 2) boundary_[u] |= uint8_t(1u << other);
    });
  }
  for (uint32_t t : ring_) {
    alive_[t] = 0;
    --live_tets_;
    if (vanished) vanished->push_back(t);
  }
  // vt's corners become vs's: relabel them, and vs's list is vt's live
  // corners followed by its own.
  forEachTet(vt, [&](uint32_t t, uint32_t corner) { tets_[t][corner] = vs; });
  const uint32_t moved = stars_.size(vt), own = stars_.size(vs);
  stars_.reserve(vs, moved + own);  // may move the pool: pointers after it
  uint32_t* into = stars_.data(vs);
  std::copy_backward(into, into + own, into + moved + own);
  std::copy_n(stars_.data(vt), moved, into);
  stars_.resize(vs, moved + own);
  stars_.clear(vt);
  boundary_vertex_[vs] |= boundary_vertex_[vt];
  --live_vertices_;
}

}  // namespace mrsv::tetsimplify
