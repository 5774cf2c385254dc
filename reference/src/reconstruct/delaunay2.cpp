// spec: 8.4 the Delaunay triangulation of the mesh's vertices.
#include "reconstruct/delaunay2.h"

namespace mrsv::reconstruct {

namespace {
constexpr int kNext[3] = {1, 2, 0};  // (i + 1) % 3 without a division
}  // namespace

Delaunay2::Delaunay2(int32_t max_x, int32_t max_y, const uint64_t* corner_ranks) {
  points_ = {{0, 0}, {max_x, 0}, {max_x, max_y}, {0, max_y}};
  ranks_ = {0, 1, 2, 3};
  if (corner_ranks) ranks_.assign(corner_ranks, corner_ranks + 4);
  for (uint32_t v = 0; v < 4; ++v) ranks_are_numbers_ = ranks_are_numbers_ && ranks_[v] == v;
  // The diagonal the perturbed test picks: (0,0)-(max,max) unless (0,max)
  // conflicts with the triangle below it.
  tri_.resize(2);
  if (!conflict(0, 1, 2, 3)) {
    set(0, 0, 1, 2, kNone, 1, kNone);
    set(1, 0, 2, 3, kNone, kNone, 0);
  } else {
    set(0, 0, 1, 3, 1, kNone, kNone);
    set(1, 1, 2, 3, kNone, 0, kNone);
  }
}

uint32_t Delaunay2::locate(Point2 p, uint32_t t) const {
  // The visibility walk ends in a Delaunay triangulation (no cycles).
  for (;;) {
    const auto& v = tri_[t].v;
    int i = 0;
    for (; i < 3; ++i)
      if (orient2d(points_[v[(i + 1) % 3]], points_[v[(i + 2) % 3]], p) < 0) break;
    if (i == 3) return t;
    t = tri_[t].n[i];
  }
}

uint32_t Delaunay2::insert(Point2 p, uint64_t rank, uint32_t t, std::vector<uint32_t>* touched) {
  const uint32_t pv = static_cast<uint32_t>(points_.size());
  points_.push_back(p);
  ranks_.push_back(rank);
  ranks_are_numbers_ = ranks_are_numbers_ && rank == pv;
  const auto v = tri_[t].v;
  const auto n = tri_[t].n;
  prefetch(n[0]), prefetch(n[1]), prefetch(n[2]);
  int on_edge = -1;
  for (int i = 0; i < 3; ++i)
    if (orient2d(points_[v[(i + 1) % 3]], points_[v[(i + 2) % 3]], p) == 0) on_edge = i;

  stack_.clear();
  if (on_edge < 0) {
    // Inside: three triangles around p, each with p as corner 0.
    const uint32_t a = v[0], b = v[1], c = v[2];
    const uint32_t t1 = addTriangle(), t2 = addTriangle();
    set(t, pv, a, b, n[2], t1, t2);
    set(t1, pv, b, c, n[0], t2, t);
    set(t2, pv, c, a, n[1], t, t1);
    replaceNeighbourToTest(n[0], t, t1);
    replaceNeighbourToTest(n[1], t, t2);
    stack_.push_back(t), stack_.push_back(t1), stack_.push_back(t2);
  } else {
    // On the edge b-c opposite a.
    const int i = on_edge;
    const uint32_t a = v[i], b = v[(i + 1) % 3], c = v[(i + 2) % 3];
    const uint32_t nb = n[(i + 1) % 3], nc = n[(i + 2) % 3], u = n[i];
    const uint32_t t1 = addTriangle();
    if (u == kNone) {
      set(t, pv, a, b, nc, kNone, t1);
      set(t1, pv, c, a, nb, t, kNone);
      replaceNeighbour(nb, t, t1);
      stack_.push_back(t), stack_.push_back(t1);
    } else {
      const int k = edgeTo(u, t);
      const uint32_t d = tri_[u].v[k];
      const uint32_t mb = tri_[u].n[(k + 2) % 3];  // across d-c (opposite b in u = (d, c, b))
      const uint32_t mc = tri_[u].n[(k + 1) % 3];  // across b-d
      const uint32_t u1 = addTriangle();
      set(t, pv, a, b, nc, u1, t1);
      set(t1, pv, c, a, nb, t, u);
      set(u, pv, d, c, mb, t1, u1);
      set(u1, pv, b, d, mc, u, t);
      replaceNeighbourToTest(nb, t, t1);
      replaceNeighbourToTest(mc, u, u1);
      stack_.push_back(t), stack_.push_back(t1), stack_.push_back(u), stack_.push_back(u1);
    }
  }
  if (touched) touched->insert(touched->end(), stack_.begin(), stack_.end());
  legalize(touched);
  return pv;
}

void Delaunay2::legalize(std::vector<uint32_t>* touched) {
  while (!stack_.empty()) {
    const uint32_t t = stack_.back();
    stack_.pop_back();
    const uint32_t u = tri_[t].n[0];
    if (u == kNone) continue;
    const uint32_t p = tri_[t].v[0], a1 = tri_[t].v[1], a2 = tri_[t].v[2];
    const int k = edgeTo(u, t);
    const uint32_t q = tri_[u].v[k];
    if (!conflict(p, a1, a2, q)) continue;
    // Flip a1-a2 to p-q: t = (p, a1, q), u = (p, q, a2).
    const uint32_t t1 = tri_[t].n[1], t2 = tri_[t].n[2];                   // across a2-p, p-a1
    const uint32_t u1 = tri_[u].n[kNext[k]], u2 = tri_[u].n[kNext[kNext[k]]];  // across a1-q, q-a2
    prefetch(u2);  // u's edge 0 after the flip, the next tested
    set(t, p, a1, q, u1, u, t2);
    set(u, p, q, a2, u2, t1, t);
    replaceNeighbourToTest(u1, u, t);
    replaceNeighbour(t1, t, u);
    stack_.push_back(t);
    stack_.push_back(u);
    if (touched) touched->push_back(t), touched->push_back(u);
  }
}

}  // namespace mrsv::reconstruct
