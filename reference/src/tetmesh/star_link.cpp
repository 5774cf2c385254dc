// spec: 7.6.1 the link of a vertex and its rotations, as a decoded split needs them.
#include "tetmesh/star_link.h"

#include <algorithm>

namespace mrsv {

// A repeated edge (no manifold) keeps its first triangle, as
// Link::triangleFrom finds it.
inline void StarLink::insert(uint32_t a, uint32_t b, uint32_t third, uint32_t f) {
  if (dense_used_) {
    const uint32_t e = a * kDense + b;
    if (dense_stamp_[e] == stamp_) return;
    dense_stamp_[e] = stamp_;
    dense_triangle_[e] = f;
    dense_third_[e] = third;
    return;
  }
  const uint64_t key = (uint64_t{a} << 32) | b;
  uint32_t e = slotOf(key);
  while (edge_key_[e] != kEmpty && edge_key_[e] != key) e = (e + 1) & mask_;
  if (edge_key_[e] == key) return;
  edge_key_[e] = key;
  edge_triangle_[e] = f;
  edge_third_[e] = third;
}

void StarLink::build(const TetComplex& mesh, uint32_t v) {
  center = v;
  const std::vector<uint32_t>& star = mesh.incident[v];
  const uint32_t faces = static_cast<uint32_t>(star.size());
  // The decoder adds a vertex per split: grown by half at a time, the
  // tables are not resized (and their new entries filled) at every split.
  if (stamp_of_.size() < mesh.positions.size()) {
    const size_t size = std::max(mesh.positions.size(), stamp_of_.size() + stamp_of_.size() / 2);
    stamp_of_.resize(size, 0);
    local_of_.resize(size, 0);
  }
  if (dense_stamp_.empty()) {
    dense_stamp_.assign(kDense * kDense, 0);
    dense_triangle_.resize(kDense * kDense);
    dense_third_.resize(kDense * kDense);
  }
  if (++stamp_ == 0) {
    std::fill(stamp_of_.begin(), stamp_of_.end(), 0);
    std::fill(dense_stamp_.begin(), dense_stamp_.end(), 0);
    stamp_ = 1;
  }
  // The triangles as vertex numbers and the link's vertices, then ascending
  // local numbers (7.6.1), as Link builds them.
  triangles.resize(faces);
  triangle_tet.assign(star.begin(), star.end());
  // Collected in gathered_, which only grows: resizing `vertices` up to
  // 3 * faces and back down at every split filled it each time.
  if (gathered_.size() < 3 * size_t{faces}) gathered_.resize(3 * size_t{faces});
  uint32_t* gathered = gathered_.data();
  uint32_t m = 0;
  for (uint32_t f = 0; f < faces; ++f) {
    const Tet& t = mesh.tets[star[f]];
    const int at = t[0] == v ? 0 : t[1] == v ? 1 : t[2] == v ? 2 : 3;
    for (int j = 0; j < 3; ++j) {
      const uint32_t u = t[kLinkOrder[at][j]];
      triangles[f][j] = u;
      if (stamp_of_[u] != stamp_) {
        stamp_of_[u] = stamp_;
        gathered[m++] = u;
      }
    }
  }
  vertices.assign(gathered, gathered + m);
  std::sort(vertices.begin(), vertices.end());
  for (uint32_t i = 0; i < m; ++i) local_of_[vertices[i]] = i;
  // The directed edges: dense_ for small links, else a hash table at most
  // half full.
  dense_used_ = m <= kDense;
  if (!dense_used_) {
    uint32_t capacity = 16;
    shift_ = 60;
    while (capacity < 6 * faces) capacity *= 2, --shift_;
    mask_ = capacity - 1;
    edge_key_.assign(capacity, kEmpty);
    edge_triangle_.resize(capacity);
    edge_third_.resize(capacity);
  }
  for (uint32_t f = 0; f < faces; ++f) {
    std::array<uint32_t, 3>& tri = triangles[f];
    const uint32_t a = local_of_[tri[0]], b = local_of_[tri[1]], c = local_of_[tri[2]];
    tri = {a, b, c};
    insert(a, b, c, f);
    insert(b, c, a, f);
    insert(c, a, b, f);
  }
  // spec 7.3: every level's links are spheres or disks, and a sphere on m
  // vertices has exactly 2m - 4 triangles, a disk fewer: only a link with
  // another count can have a boundary edge, and only then are its edges
  // scanned for one.
  on_boundary.assign(m, 0);
  has_boundary = false;
  if (uint64_t{faces} + 4 != 2 * uint64_t{m}) {
    for (const auto& tri : triangles)
      for (int j = 0; j < 3; ++j) {
        const uint32_t a = tri[j], b = tri[(j + 1) % 3];
        if (find(b, a) == kNone) {
          on_boundary[a] = on_boundary[b] = 1;
          has_boundary = true;
        }
      }
  }
}

uint32_t StarLink::lowestNeighbour(uint32_t p) const {
  // Around an interior p (where cut() asks) its neighbours form one cycle of
  // next(p, .): from the first neighbour found, follow it. Should it break,
  // every triangle through p is looked at instead.
  uint32_t first = UINT32_MAX;
  for (uint32_t f = 0; f < triangles.size() && first == UINT32_MAX; ++f)
    for (int j = 0; j < 3; ++j)
      if (triangles[f][j] == p) first = triangles[f][(j + 1) % 3];
  if (first == UINT32_MAX) return first;
  uint32_t lowest = first;
  for (uint32_t x = first, steps = 0; steps < vertices.size(); ++steps) {
    const uint32_t e = find(p, x);
    if (e == kNone) break;
    x = thirdOf(e);
    if (x == first) return lowest;
    lowest = std::min(lowest, x);
  }
  lowest = UINT32_MAX;
  for (const auto& tri : triangles)
    for (int j = 0; j < 3; ++j)
      if (tri[j] == p) lowest = std::min(lowest, tri[(j + 1) % 3]);
  return lowest;
}

bool StarLink::rotation(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const {
  out->clear();
  const size_t m = vertices.size();
  if (!on_boundary[p]) {
    // The cycle of next(p, .) from start back to start; no neighbour twice.
    uint32_t x = start;
    while (true) {
      const uint32_t e = find(p, x);
      if (e == kNone) return false;
      out->push_back(x);
      x = thirdOf(e);
      if (x == start) return true;
      if (out->size() >= m) return false;
    }
  }
  // A boundary p: back from any neighbour to the x with p -> x a boundary
  // edge (no triangle holds x -> p), then forward to the fan's other end.
  uint32_t x = UINT32_MAX;
  for (const auto& tri : triangles) {
    for (int j = 0; j < 3 && x == UINT32_MAX; ++j)
      if (tri[j] == p) x = tri[(j + 1) % 3];
    if (x != UINT32_MAX) break;
  }
  if (x == UINT32_MAX) return false;
  for (size_t steps = 0;; ++steps) {
    const uint32_t e = find(x, p);
    if (e == kNone) break;
    if (steps >= m) return false;  // a closed fan: p has no boundary edge
    x = thirdOf(e);
  }
  while (true) {
    out->push_back(x);
    const uint32_t e = find(p, x);
    if (e == kNone) return out->size() >= 2;
    if (out->size() > m) return false;
    x = thirdOf(e);
  }
}

}  // namespace mrsv
