// Is a tet complex a 3-manifold with boundary? Faces, edge links and vertex
// links, each checked from sorted local lists (no search over the mesh).
#include <algorithm>
#include <numeric>

#include "metrics/tet_faces.h"
#include "mrsv/tet_metrics.h"

namespace mrsv {
namespace {

// Union-find over a small local index range, reset between uses by the
// caller touching only what it used.
struct LocalUnionFind {
  std::vector<uint32_t> parent;
  void reset(size_t n) {
    if (parent.size() < n) parent.resize(n);
    std::iota(parent.begin(), parent.begin() + static_cast<std::ptrdiff_t>(n), 0u);
  }
  uint32_t find(uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  // True when x and y were in different sets.
  bool unite(uint32_t x, uint32_t y) {
    x = find(x);
    y = find(y);
    if (x == y) return false;
    parent[std::max(x, y)] = std::min(x, y);
    return true;
  }
};

}  // namespace

TetManifoldReport checkTetManifold(const TetMesh& mesh) {
  TetManifoldReport r;
  // Faces: one or two uses, and two uses orient the face oppositely.
  const std::vector<TetFaceUse> uses = sortedTetFaces(mesh);
  for (size_t i = 0; i < uses.size();) {
    size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const bool over = j - i > 2;
    const bool same = j - i == 2 && uses[i].odd == uses[i + 1].odd;
    r.overshared_faces += over;
    r.misoriented_faces += same;
    if ((over || same) && (r.first_bad_face_tet < 0 || uses[i].tet < r.first_bad_face_tet))
      r.first_bad_face_tet = uses[i].tet;
    i = j;
  }

  // Tets around each vertex (CSR).
  const size_t nv = mesh.positions.size();
  std::vector<uint32_t> start(nv + 1, 0);
  for (const auto& t : mesh.tets)
    for (uint32_t v : t) ++start[v + 1];
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<uint32_t> around(start[nv]);
  {
    std::vector<uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t t = 0; t < mesh.tets.size(); ++t)
      for (uint32_t v : mesh.tets[t]) around[fill[v]++] = static_cast<uint32_t>(t);
  }

  // The link of v: the faces opposite v in its tets. With local vertex ids
  // (the link's vertices, ascending) it is checked as a surface, and the
  // link of each edge (v, w), w > v, as the edges opposite w in the link
  // faces holding w.
  std::vector<uint32_t> link_vertices;
  std::vector<std::array<uint32_t, 3>> link_faces;  // local ids
  std::vector<uint64_t> link_edges;                 // (low << 32) | high, local ids
  struct Opposite {
    uint32_t w, x, y;  // link vertex w and the link edge (x, y) opposite it
  };
  std::vector<Opposite> opposite;
  LocalUnionFind uf;
  for (size_t v = 0; v < nv; ++v) {
    const uint32_t begin = start[v], end = start[v + 1];
    if (begin == end) {
      ++r.unused_vertices;
      continue;
    }
    link_vertices.clear();
    link_faces.clear();
    for (uint32_t k = begin; k < end; ++k) {
      const auto& tet = mesh.tets[around[k]];
      const int corner = static_cast<int>(std::find(tet.begin(), tet.end(), v) - tet.begin());
      link_faces.push_back(outwardFace(tet, corner));
      for (uint32_t w : link_faces.back()) link_vertices.push_back(w);
    }
    std::sort(link_vertices.begin(), link_vertices.end());
    link_vertices.erase(std::unique(link_vertices.begin(), link_vertices.end()),
                        link_vertices.end());
    auto local = [&](uint32_t w) {
      return static_cast<uint32_t>(std::lower_bound(link_vertices.begin(), link_vertices.end(), w) -
                                   link_vertices.begin());
    };
    link_edges.clear();
    opposite.clear();
    for (auto& f : link_faces) {
      for (uint32_t& w : f) w = local(w);
      for (int e = 0; e < 3; ++e) {
        const uint32_t x = f[e], y = f[(e + 1) % 3], z = f[(e + 2) % 3];
        link_edges.push_back((static_cast<uint64_t>(std::min(x, y)) << 32) | std::max(x, y));
        opposite.push_back({z, x, y});
      }
    }
    std::sort(link_edges.begin(), link_edges.end());
    // A sphere or a disk: every link edge in one or two link faces, one
    // component, and Euler characteristic 2 without border, 1 with.
    bool ok = true;
    uint64_t edges = 0, border = 0;
    uf.reset(link_vertices.size());
    uint64_t components = link_vertices.size();
    for (size_t i = 0; i < link_edges.size();) {
      size_t j = i + 1;
      while (j < link_edges.size() && link_edges[j] == link_edges[i]) ++j;
      ok = ok && j - i <= 2;
      border += j - i == 1;
      ++edges;
      components -= uf.unite(static_cast<uint32_t>(link_edges[i] >> 32),
                             static_cast<uint32_t>(link_edges[i] & 0xffffffffu));
      i = j;
    }
    const auto euler = static_cast<int64_t>(link_vertices.size()) - static_cast<int64_t>(edges) +
                       static_cast<int64_t>(link_faces.size());
    ok = ok && components == 1 && euler == (border ? 1 : 2);
    if (!ok) {
      ++r.nonmanifold_vertices;
      if (r.first_bad_vertex < 0) r.first_bad_vertex = static_cast<int64_t>(v);
    }

    // Edge links: the edges opposite w must form one path or one cycle.
    // Their vertices have degree <= 2 when every link edge is in at most two
    // link faces (checked above), so one component is what remains.
    std::sort(opposite.begin(), opposite.end(),
              [](const Opposite& a, const Opposite& b) { return a.w < b.w; });
    for (size_t i = 0; i < opposite.size();) {
      size_t j = i + 1;
      while (j < opposite.size() && opposite[j].w == opposite[i].w) ++j;
      if (link_vertices[opposite[i].w] > v) {
        // Components = vertices - successful unions. Only the entries this
        // edge link touches are reset, so the work is linear in its size.
        link_edges.clear();  // reused: the edge link's vertices
        for (size_t k = i; k < j; ++k) {
          uf.parent[opposite[k].x] = opposite[k].x;
          uf.parent[opposite[k].y] = opposite[k].y;
          link_edges.push_back(opposite[k].x);
          link_edges.push_back(opposite[k].y);
        }
        uint64_t unions = 0;
        for (size_t k = i; k < j; ++k) unions += uf.unite(opposite[k].x, opposite[k].y);
        std::sort(link_edges.begin(), link_edges.end());
        const auto count = static_cast<uint64_t>(std::unique(link_edges.begin(), link_edges.end()) -
                                                 link_edges.begin());
        if (count - unions != 1) {
          ++r.nonmanifold_edges;
          if (r.first_bad_edge < 0) r.first_bad_edge = static_cast<int64_t>(v);
        }
      }
      i = j;
    }
  }
  return r;
}

}  // namespace mrsv
