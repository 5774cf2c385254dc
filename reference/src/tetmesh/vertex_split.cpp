// spec: 7.6.3 the region of a cut, 7.6.4 applying a vertex split.
#include "tetmesh/vertex_split.h"

#include <algorithm>

namespace mrsv {

namespace {

template <class LinkT>
std::string regionOf(const LinkT& link, const std::vector<uint32_t>& walk, bool closed, SplitScratch* s,
                     std::vector<uint32_t>* region_tets) {
  const uint32_t m = static_cast<uint32_t>(link.vertices.size());
  const uint32_t k = static_cast<uint32_t>(walk.size());
  s->walk_position.assign(m, 0);
  for (uint32_t i = 0; i < k; ++i) s->walk_position[walk[i]] = i + 1;
  // An edge of the cut: consecutive on the walk (or its last and first when closed).
  auto onCut = [&](uint32_t a, uint32_t b) {
    const uint32_t pa = s->walk_position[a], pb = s->walk_position[b];
    if (pa == 0 || pb == 0) return false;
    const uint32_t d = pa > pb ? pa - pb : pb - pa;
    return d == 1 || (closed && d == k - 1);
  };
  // The queue holds each triangle at most once (when its side turns from 0
  // to 1): sized to the triangle count up front and written by index, as
  // push_back's capacity checks and calls cost a sixth of the flood.
  const size_t faces = link.triangles.size();
  s->triangle_side.assign(faces, 0);
  s->queue.resize(faces);
  uint32_t* queue = s->queue.data();
  uint32_t tail = 0;
  const uint32_t edges = cutEdgeCount(k, closed);
  for (uint32_t i = 0; i < edges; ++i) {
    const uint32_t a = walk[i], b = walk[nextOnCut(i, k)];
    // vt's side holds the directed edge b -> a, vs's side a -> b.
    const int64_t vt_side = link.triangleFrom(b, a), vs_side = link.triangleFrom(a, b);
    if (vt_side < 0 || vs_side < 0) return "the cut runs along the boundary of the link";
    if (s->triangle_side[vs_side] == 1 || s->triangle_side[vt_side] == 2)
      return "the cut does not separate the link";
    s->triangle_side[vs_side] = 2;
    if (s->triangle_side[vt_side] == 0) {
      s->triangle_side[vt_side] = 1;
      queue[tail++] = static_cast<uint32_t>(vt_side);
    }
  }
  // Steps from triangle f across its edge from corner j to corner j + 1
  // (a, b). The three edges are spelled out: a loop over j with (j + 1) % 3
  // costs about a tenth of the decoder's flood (issue 21's profile).
  auto step = [&](uint32_t f, int j, uint32_t a, uint32_t b) {
    if (onCut(a, b)) return true;
    const int64_t g = link.across(f, j);
    if (g < 0) return true;
    if (s->triangle_side[g] == 2) return false;
    if (s->triangle_side[g] == 0) {
      s->triangle_side[g] = 1;
      queue[tail++] = static_cast<uint32_t>(g);
    }
    return true;
  };
  for (uint32_t q = 0; q < tail; ++q) {
    const uint32_t f = queue[q];
    const auto tri = link.triangles[f];
    if (!step(f, 0, tri[0], tri[1]) || !step(f, 1, tri[1], tri[2]) || !step(f, 2, tri[2], tri[0]))
      return "the cut does not separate the link";
  }
  s->queue.resize(tail);
  region_tets->resize(tail);
  for (uint32_t q = 0; q < tail; ++q) (*region_tets)[q] = link.triangle_tet[queue[q]];
  return "";
}

}  // namespace

std::string splitRegion(const Link& link, const std::vector<uint32_t>& walk, bool closed, SplitScratch* scratch,
                        std::vector<uint32_t>* region_tets) {
  return regionOf(link, walk, closed, scratch, region_tets);
}

std::string splitRegion(const StarLink& link, const std::vector<uint32_t>& walk, bool closed, SplitScratch* scratch,
                        std::vector<uint32_t>* region_tets) {
  return regionOf(link, walk, closed, scratch, region_tets);
}

namespace {

Tet replaced(Tet t, uint32_t from, uint32_t to) {
  for (uint32_t& v : t)
    if (v == from) v = to;
  return t;
}

}  // namespace

namespace {

// 7.6.4 step 2: vt's list (new) takes the moved tets, which take vt in vs's
// place; `drop_moved` takes them out of vs's list; the new tets follow in cut
// order.
template <class DropMoved>
void moveAndAdd(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length, bool closed,
                const uint32_t* moved, uint32_t moved_count, DropMoved drop_moved) {
  const uint32_t edges = cutEdgeCount(walk_length, closed);
  const uint32_t first_new = static_cast<uint32_t>(mesh->tets.size());
  IncidenceLists& incident = mesh->incident;
  // vt's list is new: sized once for its moved and new tets.
  incident.reserve(vt, moved_count + edges);
  for (uint32_t i = 0; i < moved_count; ++i) incident.push(vt, moved[i]);
  for (uint32_t i = 0; i < moved_count; ++i) mesh->tets[moved[i]] = replaced(mesh->tets[moved[i]], vs, vt);
  drop_moved();
  for (uint32_t i = 0; i < edges; ++i) {
    const uint32_t a = walk[i], b = walk[nextOnCut(i, walk_length)];
    const uint32_t slot = first_new + i;
    mesh->tets.push_back(Tet{vt, a, b, vs});
    incident.push(vs, slot);
    incident.push(vt, slot);
    incident.push(a, slot);
    incident.push(b, slot);
  }
}

}  // namespace

std::string applySplit(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length,
                       bool closed, const uint32_t* moved, uint32_t moved_count) {
  const uint32_t edges = cutEdgeCount(walk_length, closed);
  for (uint32_t i = 0; i < moved_count; ++i)
    if (mesh->orientation(replaced(mesh->tets[moved[i]], vs, vt)) <= 0)
      return "tet " + std::to_string(moved[i]) + " would not be positive with vt in place of vs";
  for (uint32_t i = 0; i < edges; ++i) {
    const Tet t{vt, walk[i], walk[nextOnCut(i, walk_length)], vs};
    if (mesh->orientation(t) <= 0)
      return "the new tet at cut edge " + std::to_string(i) + " would not be positive";
  }
  moveAndAdd(mesh, vs, vt, walk, walk_length, closed, moved, moved_count, [&] {
    // vs keeps the tets that did not move: those that still have vs as a
    // corner (a moved tet has vt in its place now, and no tet repeats a
    // corner). The order of the rest is kept.
    IncidenceLists& incident = mesh->incident;
    const auto& tets = mesh->tets;
    uint32_t* star_vs = incident.data(vs);
    uint32_t kept = 0;
    for (uint32_t f = 0; f < incident.size(vs); ++f) {
      const Tet& k = tets[star_vs[f]];
      if (k[0] == vs || k[1] == vs || k[2] == vs || k[3] == vs) star_vs[kept++] = star_vs[f];
    }
    incident.resize(vs, kept);
  });
  return "";
}

void redoSplit(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length, bool closed,
               const uint32_t* moved, uint32_t moved_count) {
  moveAndAdd(mesh, vs, vt, walk, walk_length, closed, moved, moved_count, [&] {
    // Both in increasing slot order, `moved` a subsequence of vs's list.
    IncidenceLists& incident = mesh->incident;
    uint32_t* star_vs = incident.data(vs);
    const uint32_t n = incident.size(vs);
    uint32_t kept = 0, next = 0;
    for (uint32_t f = 0; f < n; ++f) {
      const uint32_t slot = star_vs[f];
      const bool is_moved = next < moved_count && moved[next] == slot;
      star_vs[kept] = slot;
      kept += !is_moved;
      next += is_moved;
    }
    incident.resize(vs, kept);
  });
}

void undoSplit(TetComplex* mesh, uint32_t vs, uint32_t vt, const uint32_t* walk, uint32_t walk_length,
               bool closed, const uint32_t* moved, uint32_t moved_count) {
  const uint32_t edges = cutEdgeCount(walk_length, closed);
  // The new tets are the last slots (every later split has been undone), so
  // the last entries of their lists.
  IncidenceLists& incident = mesh->incident;
  for (uint32_t i = 0; i < edges; ++i) {
    incident.pop(walk[i]);
    incident.pop(walk[nextOnCut(i, walk_length)]);
  }
  const uint32_t n = incident.size(vs) - edges;
  mesh->tets.resize(mesh->tets.size() - edges);
  for (uint32_t i = 0; i < moved_count; ++i) mesh->tets[moved[i]] = replaced(mesh->tets[moved[i]], vt, vs);
  // vs's list and `moved` merged from their ends, in place; which side gives
  // the next entry is not predictable, so no branch on it (a branch there
  // was two thirds of undoing a split on the CT crop, perf).
  incident.reserve(vs, n + moved_count);  // may move the pool: the pointer after it
  uint32_t* star_vs = incident.data(vs);
  uint32_t from = n, next = moved_count, to = n + moved_count;
  while (next > 0) {
    const uint32_t kept = from > 0 ? star_vs[from - 1] : 0, back = moved[next - 1];
    const bool take_kept = from > 0 && kept > back;
    star_vs[--to] = take_kept ? kept : back;
    from -= take_kept;
    next -= !take_kept;
  }
  incident.resize(vs, n + moved_count);
  incident.clear(vt);
}

}  // namespace mrsv
