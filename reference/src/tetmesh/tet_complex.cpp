// spec: 7.3 the mesh a PT decoder holds, 7.6.1 links.
#include "tetmesh/tet_complex.h"

#include <algorithm>

namespace mrsv {

int64_t Link::triangleFrom(uint32_t p, uint32_t q) const {
  for (uint32_t k = corner_begin[p]; k < corner_begin[p + 1]; ++k)
    if (corners[k][0] == q) return corners[k][2];
  return -1;
}

uint32_t Link::lowestNeighbour(uint32_t p) const {
  uint32_t lowest = UINT32_MAX;
  for (uint32_t k = corner_begin[p]; k < corner_begin[p + 1]; ++k) lowest = std::min(lowest, corners[k][0]);
  return lowest;
}

uint32_t Link::localIndex(uint32_t vertex) const {
  auto it = std::lower_bound(vertices.begin(), vertices.end(), vertex);
  return it != vertices.end() && *it == vertex ? static_cast<uint32_t>(it - vertices.begin())
                                               : static_cast<uint32_t>(vertices.size());
}

bool Link::rotation(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const {
  out->clear();
  const uint32_t begin = corner_begin[p], end = corner_begin[p + 1];
  const uint32_t deg = end - begin;
  if (deg == 0) return false;
  uint32_t k = UINT32_MAX;
  for (uint32_t j = begin; j < end && k == UINT32_MAX; ++j)
    if (on_boundary[p] ? corner_prev[j] == UINT32_MAX : corners[j][0] == start) k = j;
  if (k == UINT32_MAX) return false;
  out->push_back(corners[k][0]);
  // Around an interior p the corners form one cycle, around a boundary p one path.
  for (uint32_t step = 0; step < deg; ++step) {
    out->push_back(corners[k][1]);
    // Back at the start early: the corners form several cycles (a pinch).
    if (step + 1 < deg && corners[k][1] == out->front()) return false;
    k = corner_next[k];
    if (k == UINT32_MAX) break;
  }
  if (on_boundary[p]) return k == UINT32_MAX && out->size() == deg + 1;
  if (k == UINT32_MAX || out->back() != out->front()) return false;
  out->pop_back();
  return out->size() == deg;
}

void TetComplex::buildIncidence() {
  incident.assign(static_cast<uint32_t>(positions.size()));
  for (uint32_t t = 0; t < tets.size(); ++t)
    for (uint32_t v : tets[t]) incident.push(v, t);
}

void TetComplex::buildLink(uint32_t v, Link* link) const {
  // One pass over the star for the triangles (as vertex numbers) and the
  // link's vertices, a sort, then the triangles in local numbers and the
  // corners per local vertex. Every array is sized once and written by
  // index: at about 30 tets per star, vector growth checks, fills and extra
  // passes cost more than the work itself (issue 21's profile).
  Link& l = *link;
  l.center = v;
  const IncidenceLists::View star = incident.of(v);
  const uint32_t faces = static_cast<uint32_t>(star.size());
  if (l.stamp_of.size() < positions.size()) {
    l.stamp_of.resize(positions.size(), 0);
    l.local_of.resize(positions.size(), 0);
  }
  if (++l.stamp == 0) {
    std::fill(l.stamp_of.begin(), l.stamp_of.end(), 0);
    l.stamp = 1;
  }
  l.triangles.resize(faces);
  l.triangle_tet.assign(star.begin(), star.end());
  l.vertices.resize(3 * size_t{faces});
  uint32_t m = 0;
  {
    uint32_t* stamp_of = l.stamp_of.data();
    uint32_t* vertices = l.vertices.data();
    const uint32_t stamp = l.stamp;
    for (uint32_t f = 0; f < faces; ++f) {
      const Tet& t = tets[star[f]];
      const int at = t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : 3;
      std::array<uint32_t, 3>& tri = l.triangles[f];
      for (int j = 0; j < 3; ++j) {
        const uint32_t u = t[kLinkOrder[at][j]];
        tri[j] = u;
        if (stamp_of[u] != stamp) {
          stamp_of[u] = stamp;
          vertices[m++] = u;
        }
      }
    }
  }
  l.vertices.resize(m);
  std::sort(l.vertices.begin(), l.vertices.end());
  for (uint32_t i = 0; i < m; ++i) l.local_of[l.vertices[i]] = i;
  // CSR of the corners per local vertex: counts at p + 2, their prefix sums
  // at p + 1, then each corner placed by bumping its vertex's cursor.
  l.corner_begin.assign(m + 2, 0);
  const uint32_t corner_count = 3 * faces;
  l.corners.resize(corner_count);
  l.triangle_corner.resize(faces);
  l.corner_next.resize(corner_count);
  l.corner_prev.assign(corner_count, UINT32_MAX);
  if (l.corner_of_q.size() < m) l.corner_of_q.resize(m);
  l.on_boundary.assign(m, 0);
  // The loops below run on raw pointers: through the vectors the compiler
  // reloads every base pointer after each store.
  std::array<uint32_t, 3>* triangles = l.triangles.data();
  uint32_t* begin_of = l.corner_begin.data();
  const uint32_t* local_of = l.local_of.data();
  std::array<uint32_t, 3>* corners = l.corners.data();
  std::array<uint32_t, 3>* triangle_corner = l.triangle_corner.data();
  uint32_t* next = l.corner_next.data();
  uint32_t* prev = l.corner_prev.data();
  uint32_t* corner_of_q = l.corner_of_q.data();
  uint8_t* on_boundary = l.on_boundary.data();
  for (uint32_t f = 0; f < faces; ++f)
    for (uint32_t& p : triangles[f]) {
      p = local_of[p];
      ++begin_of[p + 2];
    }
  for (uint32_t p = 0; p < m; ++p) begin_of[p + 2] += begin_of[p + 1];
  for (uint32_t f = 0; f < faces; ++f) {
    const auto& tri = triangles[f];
    for (int j = 0; j < 3; ++j) {
      const uint32_t k = begin_of[tri[j] + 1]++;
      corners[k] = {tri[(j + 1) % 3], tri[(j + 2) % 3], f};
      triangle_corner[f][j] = k;
    }
  }
  l.corner_begin.pop_back();
  // Around each p: which corner follows which (q -> r, then r -> ...), and
  // which corners nothing leads to (they start the fan of a boundary p).
  bool has_boundary = false;
  for (uint32_t p = 0; p < m; ++p) {
    const uint32_t begin = begin_of[p], end = begin_of[p + 1];
    // corner_of_q[q] may be left from an earlier p or link: the range and
    // the check that the corner starts at q below reject such an entry.
    for (uint32_t k = begin; k < end; ++k) corner_of_q[corners[k][0]] = k;
    for (uint32_t k = begin; k < end; ++k) {
      const uint32_t r = corners[k][1];
      const uint32_t j = corner_of_q[r];
      if (j >= begin && j < end && corners[j][0] == r) {
        next[k] = j;
        prev[j] = k;
      } else {
        next[k] = UINT32_MAX;
      }
    }
    for (uint32_t k = begin; k < end; ++k)
      if (prev[k] == UINT32_MAX) {
        // The edge p -> q has no triangle on its other side.
        on_boundary[p] = on_boundary[corners[k][0]] = 1;
        has_boundary = true;
      }
  }
  l.has_boundary = has_boundary;
}

std::string checkLinkIsSphereOrDisk(const Link& link) {
  const uint32_t m = static_cast<uint32_t>(link.vertices.size());
  const uint32_t faces = static_cast<uint32_t>(link.triangles.size());
  if (faces == 0) return "has no tets";
  // Linear in the link's corners: the repeated neighbours of p counted in
  // one array, and an edge's other side read from the corner table (across(),
  // corner_prev) rather than searched among the neighbour's corners, which
  // made the check quadratic in the degrees (a sixth of the bunny's decode,
  // whose base mesh has stars of hundreds of tets).
  uint64_t boundary_edges = 0;
  std::vector<uint32_t> fan, count(m, 0);
  for (uint32_t p = 0; p < m; ++p) {
    const uint32_t begin = link.corner_begin[p], end = link.corner_begin[p + 1];
    for (uint32_t k = begin; k < end; ++k) ++count[link.corners[k][0]];
    // The first corner of p whose neighbour q comes again.
    for (uint32_t k = begin; k < end; ++k)
      if (count[link.corners[k][0]] > 1)
        return "faces with vertex " + std::to_string(link.vertices[p]) + " and " +
               std::to_string(link.vertices[link.corners[k][0]]) +
               " are not shared by at most two tets of opposite orientation";
    for (uint32_t k = begin; k < end; ++k) {
      count[link.corners[k][0]] = 0;
      // Without repeated neighbours, no triangle (p, x, q) ends where corner
      // (q, r) starts exactly when the edge q -> p has no triangle.
      if (link.corner_prev[k] == UINT32_MAX) ++boundary_edges;
    }
    if (!link.rotation(p, link.corners[begin][0], &fan))
      return "edge to vertex " + std::to_string(link.vertices[p]) + " is not manifold (its tets form several fans)";
  }
  // Connected: a walk over the triangles across their shared edges.
  std::vector<uint8_t> seen(faces, 0);
  std::vector<uint32_t> queue{0};
  seen[0] = 1;
  for (size_t i = 0; i < queue.size(); ++i) {
    const uint32_t f = queue[i];
    for (int j = 0; j < 3; ++j) {
      const int64_t g = link.across(f, j);
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
    if (incident.empty(v)) return "vertex " + std::to_string(v) + " is in no tet";
    buildLink(v, &link);
    std::string problem = checkLinkIsSphereOrDisk(link);
    if (!problem.empty()) return "vertex " + std::to_string(v) + ": " + problem;
  }
  return "";
}

}  // namespace mrsv
