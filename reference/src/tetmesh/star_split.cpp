// spec: 7.6.3 the region of a cut, 7.6.4 applying a split, for the decoder.
#include "tetmesh/star_split.h"

#include <algorithm>

namespace mrsv {

std::string applyStarSplit(TetComplex* mesh, StarLink* star_link, uint32_t vt, const std::vector<uint32_t>& walk,
                           bool closed, SplitScratch* s, std::vector<uint32_t>* moved,
                           std::vector<uint32_t>* walk_global) {
  const StarLink& link = *star_link;
  const uint32_t vs = link.center;
  const uint32_t k = static_cast<uint32_t>(walk.size());
  const uint32_t edges = cutEdgeCount(k, closed);
  const uint32_t m = static_cast<uint32_t>(link.vertices.size());
  const uint32_t faces = static_cast<uint32_t>(link.triangles.size());
  constexpr uint32_t kNo = StarLink::kNoTriangle;

  // 7.6.3 as splitRegion() finds it (seeds in cut order, then breadth
  // first, each triangle's edges in corner order), so that the moved tets
  // come in its order; written out on raw arrays, as the generic flood's
  // signed triangle numbers and per-step lookups cost twice as much.
  uint8_t* side = zeroedPrefix(&s->triangle_side, faces + 1);  // 0 unknown, 1 vt's, 2 vs's
  side[faces] = 1;  // where steps that are not taken go
  s->queue.resize(faces + 1);  // each triangle enters once, when its side turns 1 (+1: see step())
  uint32_t* queue = s->queue.data();
  uint32_t tail = 0;
  for (uint32_t i = 0; i < edges; ++i) {
    const uint32_t a = walk[i], b = walk[nextOnCut(i, k)];
    const uint32_t vt_side = link.triangleHolding(b, a), vs_side = link.triangleHolding(a, b);
    if (vt_side == kNo || vs_side == kNo) return "the cut runs along the boundary of the link";
    if (side[vs_side] == 1 || side[vt_side] == 2) return "the cut does not separate the link";
    side[vs_side] = 2;
    if (side[vt_side] == 0) {
      side[vt_side] = 1;
      queue[tail++] = vt_side;
    }
  }
  // No step crosses a cut edge: from a region triangle it would cross
  // towards the cut edge's vs side, the triangle holding c_i -> c_(i+1),
  // and the link is told to forget that directed edge (no other triangle
  // holds it, and a block in the region is an error before it is left). Then
  // a step is one lookup, not a test of the cut positions of its ends (a
  // third of the flood, callgrind).
  for (uint32_t i = 0; i < edges; ++i) star_link->forgetEdge(walk[i], walk[nextOnCut(i, k)]);
  // A step from a region triangle across its edge a -> b to the triangle
  // holding b -> a; false when that is a block. Whether there is one (the
  // cut, the link's boundary) and whether it is new to the region cannot be
  // predicted: no branch on either (a step not taken goes to triangle
  // `faces`, which stays on vt's side; cachegrind's branch simulation on the
  // CT crop: 24 mispredictions per split less).
  const StarLink::Lookup table = link.lookup();
  const std::array<uint32_t, 3>* triangles = link.triangles.data();
  auto step = [&](uint32_t a, uint32_t b) {
    const uint32_t g = table.triangleHolding(b, a);
    const uint32_t to = g == kNo ? faces : g;
    const uint8_t was = side[to];
    if (was == 2) return false;
    queue[tail] = to;  // kept when `to` is new; the queue has room for one more
    tail += was == 0;
    side[to] = 1;
    return true;
  };
  for (uint32_t q = 0; q < tail; ++q) {
    const auto tri = triangles[queue[q]];
    if (!step(tri[0], tri[1]) || !step(tri[1], tri[2]) || !step(tri[2], tri[0]))
      return "the cut does not separate the link";
  }
  moved->resize(tail);
  for (uint32_t q = 0; q < tail; ++q) (*moved)[q] = link.triangle_tet[queue[q]];
  walk_global->resize(k);
  for (uint32_t i = 0; i < k; ++i) (*walk_global)[i] = link.vertices[walk[i]];

  // 7.6.4 step 1: the moved tets in region order, then the new ones in cut order.
  const Point3i at = mesh->positions[vt];
  auto differenceOf = [&](uint32_t vertex) {
    const Point3i& p = mesh->positions[vertex];
    return Diff3{int64_t{p[0]} - at[0], int64_t{p[1]} - at[1], int64_t{p[2]} - at[2]};
  };
  s->difference.resize(m);
  Diff3* d = s->difference.data();
  for (uint32_t p = 0; p < m; ++p) d[p] = differenceOf(link.vertices[p]);
  const bool below_2to20 = mesh->position_bits <= 20;
  const uint32_t moved_count = static_cast<uint32_t>(moved->size());
  for (uint32_t q = 0; q < moved_count; ++q) {
    const auto& tri = link.triangles[s->queue[q]];
    if (orientOfDifferences(d[tri[0]], d[tri[1]], d[tri[2]], below_2to20) <= 0)
      return "tet " + std::to_string((*moved)[q]) + " would not be positive with vt in place of vs";
  }
  const Diff3 to_vs = differenceOf(vs);
  for (uint32_t i = 0; i < edges; ++i)
    if (orientOfDifferences(d[walk[i]], d[walk[nextOnCut(i, k)]], to_vs, below_2to20) <= 0)
      return "the new tet at cut edge " + std::to_string(i) + " would not be positive";

  // Step 2, as applySplit() does it.
  auto& tets = mesh->tets;
  const uint32_t first_new = static_cast<uint32_t>(tets.size());
  IncidenceLists& incident = mesh->incident;
  // vt's list is new: sized once for its moved and new tets and a few more,
  // so that the tets later splits give it seldom move it again.
  incident.reserve(vt, 2 * (moved_count + edges));
  // Branch-free, as which corner is vs and which tets move are not predictable.
  for (uint32_t t : *moved) {
    Tet& c = tets[t];
    c[cornerOf(c, vs)] = vt;
  }
  // vs keeps the tets of the triangles the region did not mark, in order;
  // vt's list takes the others in the same order, so that both stay in
  // increasing slot order (IncidenceLists' invariant for undoing splits),
  // and `moved` becomes that order too.
  uint32_t* star_vs = incident.data(vs);
  uint32_t* star_vt = incident.data(vt);
  uint32_t kept = 0, to_vt = 0;
  for (uint32_t f = 0; f < faces; ++f) {
    const uint32_t slot = star_vs[f];
    star_vs[kept] = slot;
    star_vt[to_vt] = slot;
    kept += side[f] != 1;
    to_vt += side[f] == 1;
  }
  incident.resize(vs, kept);
  incident.resize(vt, to_vt);
  std::copy_n(star_vt, to_vt, moved->data());
  for (uint32_t i = 0; i < edges; ++i) {
    const uint32_t a = (*walk_global)[i], b = (*walk_global)[nextOnCut(i, k)];
    const uint32_t slot = first_new + i;
    tets.push_back(Tet{vt, a, b, vs});
    incident.push(vs, slot);
    incident.push(vt, slot);
    incident.push(a, slot);
    incident.push(b, slot);
  }
  return "";
}

}  // namespace mrsv
