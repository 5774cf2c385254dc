// spec: 7.3 the mesh a PT decoder holds, 7.6.1 links.
#include "tetmesh/tet_complex.h"

#include <algorithm>

namespace mrsv {

namespace {

// spec 7.6.1: the link triangle of the corner at position i of a positive tet
// (a, b, c, d): the other three corners in the order that an even
// permutation moving corner i to the front leaves them.
constexpr int kLinkOrder[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

}  // namespace

int64_t Link::triangleFrom(uint32_t p, uint32_t q) const {
  for (uint32_t k = corner_begin[p]; k < corner_begin[p + 1]; ++k)
    if (corners[k][0] == q) return corners[k][2];
  return -1;
}

uint32_t Link::localIndex(uint32_t vertex) const {
  auto it = std::lower_bound(vertices.begin(), vertices.end(), vertex);
  return it != vertices.end() && *it == vertex ? static_cast<uint32_t>(it - vertices.begin())
                                               : static_cast<uint32_t>(vertices.size());
}

// Finds the corner of p that starts at q: its next neighbour, or UINT32_MAX.
static uint32_t nextAround(const Link& link, uint32_t p, uint32_t q) {
  for (uint32_t k = link.corner_begin[p]; k < link.corner_begin[p + 1]; ++k)
    if (link.corners[k][0] == q) return link.corners[k][1];
  return UINT32_MAX;
}

bool Link::rotation(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const {
  out->clear();
  const uint32_t deg = degree(p);
  if (deg == 0) return false;
  if (on_boundary[p]) {
    // The fan starts at the neighbour that no triangle of p ends at.
    start = UINT32_MAX;
    for (uint32_t k = corner_begin[p]; k < corner_begin[p + 1] && start == UINT32_MAX; ++k) {
      bool ends_somewhere = false;
      for (uint32_t j = corner_begin[p]; j < corner_begin[p + 1]; ++j)
        if (corners[j][1] == corners[k][0]) ends_somewhere = true;
      if (!ends_somewhere) start = corners[k][0];
    }
    if (start == UINT32_MAX) return false;
    out->push_back(start);
    for (uint32_t step = 0; step < deg; ++step) {
      const uint32_t next = nextAround(*this, p, out->back());
      if (next == UINT32_MAX) return false;
      out->push_back(next);
    }
    return nextAround(*this, p, out->back()) == UINT32_MAX;
  }
  out->push_back(start);
  for (uint32_t step = 1; step < deg; ++step) {
    const uint32_t next = nextAround(*this, p, out->back());
    if (next == UINT32_MAX || next == start) return false;
    out->push_back(next);
  }
  return nextAround(*this, p, out->back()) == start;
}

void TetComplex::buildIncidence() {
  incident.assign(positions.size(), {});
  for (uint32_t t = 0; t < tets.size(); ++t)
    for (uint32_t v : tets[t]) incident[v].push_back(t);
}

void TetComplex::buildLink(uint32_t v, Link* link) const {
  link->center = v;
  link->vertices.clear();
  link->triangles.clear();
  link->triangle_tet.clear();
  const std::vector<uint32_t>& star = incident[v];
  if (link->stamp_of.size() < positions.size()) {
    link->stamp_of.resize(positions.size(), 0);
    link->local_of.resize(positions.size(), 0);
  }
  if (++link->stamp == 0) {
    std::fill(link->stamp_of.begin(), link->stamp_of.end(), 0);
    link->stamp = 1;
  }
  for (uint32_t slot : star)
    for (uint32_t u : tets[slot])
      if (u != v && link->stamp_of[u] != link->stamp) {
        link->stamp_of[u] = link->stamp;
        link->vertices.push_back(u);
      }
  std::sort(link->vertices.begin(), link->vertices.end());
  for (uint32_t i = 0; i < link->vertices.size(); ++i) link->local_of[link->vertices[i]] = i;
  const uint32_t m = static_cast<uint32_t>(link->vertices.size());
  link->corner_begin.assign(m + 2, 0);
  for (uint32_t slot : star) {
    const Tet& t = tets[slot];
    int at = 0;
    while (at < 3 && t[at] != v) ++at;
    std::array<uint32_t, 3> tri;
    for (int j = 0; j < 3; ++j) tri[j] = link->local_of[t[kLinkOrder[at][j]]];
    link->triangles.push_back(tri);
    link->triangle_tet.push_back(slot);
    for (uint32_t p : tri) ++link->corner_begin[p + 2];
  }
  for (uint32_t p = 0; p < m; ++p) link->corner_begin[p + 2] += link->corner_begin[p + 1];
  link->corners.resize(3 * link->triangles.size());
  for (uint32_t f = 0; f < link->triangles.size(); ++f) {
    const auto& tri = link->triangles[f];
    for (int j = 0; j < 3; ++j)
      link->corners[link->corner_begin[tri[j] + 1]++] = {tri[(j + 1) % 3], tri[(j + 2) % 3], f};
  }
  link->corner_begin.pop_back();
  link->on_boundary.assign(m, 0);
  link->has_boundary = false;
  for (const auto& tri : link->triangles)
    for (int j = 0; j < 3; ++j) {
      const uint32_t a = tri[j], b = tri[(j + 1) % 3];
      if (link->triangleFrom(b, a) < 0) {
        link->on_boundary[a] = link->on_boundary[b] = 1;
        link->has_boundary = true;
      }
    }
}

std::string checkLinkIsSphereOrDisk(const Link& link) {
  const uint32_t m = static_cast<uint32_t>(link.vertices.size());
  const uint32_t faces = static_cast<uint32_t>(link.triangles.size());
  if (faces == 0) return "has no tets";
  uint64_t boundary_edges = 0;
  std::vector<uint32_t> fan;
  for (uint32_t p = 0; p < m; ++p) {
    for (uint32_t k = link.corner_begin[p]; k < link.corner_begin[p + 1]; ++k) {
      for (uint32_t j = k + 1; j < link.corner_begin[p + 1]; ++j)
        if (link.corners[j][0] == link.corners[k][0])
          return "faces with vertex " + std::to_string(link.vertices[p]) + " and " +
                 std::to_string(link.vertices[link.corners[k][0]]) +
                 " are not shared by at most two tets of opposite orientation";
      if (link.triangleFrom(link.corners[k][0], p) < 0) ++boundary_edges;
    }
    if (!link.rotation(p, link.corners[link.corner_begin[p]][0], &fan))
      return "edge to vertex " + std::to_string(link.vertices[p]) + " is not manifold (its tets form several fans)";
  }
  // Connected: a walk over the triangles across their shared edges.
  std::vector<uint8_t> seen(faces, 0);
  std::vector<uint32_t> queue{0};
  seen[0] = 1;
  for (size_t i = 0; i < queue.size(); ++i) {
    const auto& tri = link.triangles[queue[i]];
    for (int j = 0; j < 3; ++j) {
      const int64_t g = link.triangleFrom(tri[(j + 1) % 3], tri[j]);
      if (g >= 0 && !seen[g]) {
        seen[g] = 1;
        queue.push_back(static_cast<uint32_t>(g));
      }
    }
  }
  if (queue.size() != faces) return "its tets do not form one connected star (a pinched vertex)";
  const int64_t edges = (3 * int64_t{faces} + static_cast<int64_t>(boundary_edges)) / 2;
  const int64_t euler = int64_t{m} - edges + faces;
  if (boundary_edges == 0 ? euler != 2 : euler != 1)
    return std::string("its link is not a ") + (boundary_edges == 0 ? "sphere" : "disk") +
           " (Euler characteristic " + std::to_string(euler) + ")";
  return "";
}

std::string TetComplex::checkManifold() const {
  for (uint32_t t = 0; t < tets.size(); ++t) {
    const Tet& k = tets[t];
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (k[i] == k[j]) return "tet " + std::to_string(t) + " repeats vertex " + std::to_string(k[i]);
    if (orientation(k) <= 0)
      return "tet " + std::to_string(t) + (orientation(k) == 0 ? " is degenerate (orient3d = 0)"
                                                                 : " is inverted (orient3d < 0)");
  }
  Link link;
  for (uint32_t v = 0; v < positions.size(); ++v) {
    if (incident[v].empty()) return "vertex " + std::to_string(v) + " is in no tet";
    buildLink(v, &link);
    std::string problem = checkLinkIsSphereOrDisk(link);
    if (!problem.empty()) return "vertex " + std::to_string(v) + ": " + problem;
  }
  return "";
}

}  // namespace mrsv
