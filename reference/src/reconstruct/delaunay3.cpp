// spec: 10.2 (the perturbed Delaunay tetrahedralization), 10.3 (the hull).
#include "reconstruct/delaunay3.h"

#include <algorithm>
#include <cassert>

namespace mrsv::reconstruct {

bool Delaunay3::init(uint32_t sx, uint32_t sy, uint32_t sz, std::string* error) {
  for (uint32_t s : {sx, sy, sz})
    if (s < 2 || s > kMaxSide) {
      if (error) *error = "volume insertion needs grid sides from 2 to " + std::to_string(kMaxSide);
      return false;
    }
  const int32_t X = static_cast<int32_t>(sx - 1), Y = static_cast<int32_t>(sy - 1), Z = static_cast<int32_t>(sz - 1);
  small_ = sx <= 2048 && sy <= 2048 && sz <= 2048;
  points_ = {GridPoint{0, 0, 0}, GridPoint{0, 0, 0}, GridPoint{X, 0, 0}, GridPoint{0, Y, 0}, GridPoint{0, 0, Z}};
  vertex_cell_.assign(points_.size(), 0);
  cells_.clear();
  free_.clear();
  // The corner tet (O, A, B, C) is positive: det = X * Y * Z. Across each of
  // its faces an infinite cell: the face's corners with the infinite vertex
  // in the slot of the corner left out and two others swapped, so that the
  // infinite vertex stands beyond the face.
  cells_.push_back(Cell{{1, 2, 3, 4}, {kNone, kNone, kNone, kNone}});
  for (int i = 0; i < 4; ++i) {
    Cell c = {{1, 2, 3, 4}, {kNone, kNone, kNone, kNone}};
    c.v[i] = kInfinite;
    const int j = (i + 1) & 3, k = (i + 2) & 3;
    std::swap(c.v[j], c.v[k]);
    c.n[i] = 0;
    cells_[0].n[i] = static_cast<uint32_t>(cells_.size());
    cells_.push_back(c);
  }
  // The infinite cells meet each other along the hull's edges: match their
  // faces that hold the infinite vertex (five cells, a fixed cost).
  auto faceKey = [&](uint32_t c, int i) {
    std::array<uint32_t, 3> f;
    int m = 0;
    for (int k = 0; k < 4; ++k)
      if (k != i) f[m++] = cells_[c].v[k];
    std::sort(f.begin(), f.end());
    return f;
  };
  for (uint32_t a = 1; a < 5; ++a)
    for (int i = 0; i < 4; ++i) {
      if (cells_[a].n[i] != kNone) continue;
      for (uint32_t b = a + 1; b < 5 && cells_[a].n[i] == kNone; ++b)
        for (int j = 0; j < 4; ++j)
          if (cells_[b].n[j] == kNone && faceKey(a, i) == faceKey(b, j)) {
            cells_[a].n[i] = b;
            cells_[b].n[j] = a;
            break;
          }
    }
  for (uint32_t c = 0; c < 5; ++c)
    for (uint32_t v : cells_[c].v) vertex_cell_[v] = c;
  finite_cells_ = 1;
  last_cell_ = 0;
  mark_.clear();
  stamp_ = 0;
  // The other four corners, the far one first: in this order none of them
  // is ever in the plane of a hull face that is not on the box (the faces
  // around (X, Y, Z) are the only slanted ones, and each later corner is at
  // 0 or 2 XYZ of their planes' XYZ), so the coplanar hull test only meets
  // faces on the box's sides (spec 10.3).
  insert(GridPoint{X, Y, Z}, 0);
  insert(GridPoint{X, Y, 0});
  insert(GridPoint{X, 0, Z});
  insert(GridPoint{0, Y, Z});
  return true;
}

bool Delaunay3::inConflict(uint32_t c, const GridPoint& p) const {
  const Cell& t = cells_[c];
  int inf = -1;
  for (int k = 0; k < 4; ++k)
    if (t.v[k] == kInfinite) inf = k;
  if (inf < 0) {
    const GridPoint* q[4] = {&points_[t.v[0]], &points_[t.v[1]], &points_[t.v[2]], &points_[t.v[3]]};
    return small_ ? insphereConflict<int64_t>(q, p) : insphereConflict<__int128>(q, p);
  }
  const GridPoint* q[4];
  const GridPoint* f[3];
  int m = 0;
  for (int k = 0; k < 4; ++k) {
    q[k] = k == inf ? &p : &points_[t.v[k]];
    if (k != inf) f[m++] = q[k];
  }
  const int64_t o = orient3dValue(*q[0], *q[1], *q[2], *q[3]);
  if (o != 0) return o > 0;  // beyond the face, or on the hull's side
  const int axis = sharedAxis(*f[0], *f[1], *f[2]);
  assert(axis >= 0 && "a grid point in the plane of a slanted hull face");
  return coplanarCircleConflict(axis < 0 ? 2 : axis, f, p);
}

uint32_t Delaunay3::locate(const GridPoint& p, uint32_t start) const {
  uint32_t c = start;
  if (!isFinite(c))
    for (int k = 0; k < 4; ++k)
      if (cells_[c].v[k] == kInfinite) c = cells_[c].n[k];
  uint32_t prev = kNone;
  for (;;) {
    const Cell& t = cells_[c];
    // A random first face (xorshift) keeps the walk from cycling in
    // degenerate configurations; the result does not depend on it.
    walk_seed_ ^= walk_seed_ << 13;
    walk_seed_ ^= walk_seed_ >> 17;
    walk_seed_ ^= walk_seed_ << 5;
    const int r = static_cast<int>(walk_seed_ & 3);
    uint32_t next = kNone;
    for (int k = 0; k < 4 && next == kNone; ++k) {
      const int i = (r + k) & 3;
      if (t.n[i] == prev) continue;
      const GridPoint* q[4] = {&points_[t.v[0]], &points_[t.v[1]], &points_[t.v[2]], &points_[t.v[3]]};
      q[i] = &p;
      if (orient3dValue(*q[0], *q[1], *q[2], *q[3]) < 0) next = t.n[i];
    }
    if (next == kNone) return c;
    prev = c;
    c = next;
    if (!isFinite(c)) return c;
  }
}

uint32_t Delaunay3::insert(const GridPoint& p, uint32_t start) {
  if (start == kNone || start >= cells_.size() || !isLive(start)) start = last_cell_;
  return insertFrom(p, locate(p, start));
}

uint32_t Delaunay3::insertInCell(const GridPoint& p, uint32_t cell) { return insertFrom(p, cell); }

uint32_t Delaunay3::newCellSlot() {
  if (!free_.empty()) {
    const uint32_t c = free_.back();
    free_.pop_back();
    return c;
  }
  cells_.push_back(Cell{});
  return static_cast<uint32_t>(cells_.size() - 1);
}

uint32_t Delaunay3::insertFrom(const GridPoint& p, uint32_t first_conflict) {
  const uint32_t pv = static_cast<uint32_t>(points_.size());
  points_.push_back(p);
  vertex_cell_.push_back(0);

  // The conflict region: the cells whose sphere (or hull circle) holds p,
  // connected and star-shaped from p, grown from the cell that contains it.
  if (stamp_ >= UINT32_MAX - 2) {
    std::fill(mark_.begin(), mark_.end(), 0u);
    stamp_ = 0;
  }
  stamp_ += 2;
  if (mark_.size() < cells_.size()) mark_.resize(cells_.size(), 0u);
  conflict_.clear();
  boundary_.clear();
  stack_.clear();
  stack_.push_back(first_conflict);
  mark_[first_conflict] = stamp_;
  while (!stack_.empty()) {
    const uint32_t t = stack_.back();
    stack_.pop_back();
    conflict_.push_back(t);
    for (int i = 0; i < 4; ++i) {
      const uint32_t nb = cells_[t].n[i];
      if (mark_[nb] == stamp_) continue;
      if (mark_[nb] != stamp_ + 1) {
        if (inConflict(nb, p)) {
          mark_[nb] = stamp_;
          stack_.push_back(nb);
          continue;
        }
        mark_[nb] = stamp_ + 1;
      }
      Boundary b;
      for (int k = 0; k < 4; ++k) b.v[k] = cells_[t].v[k];
      b.v[i] = pv;  // p takes the slot of the corner it faces: same orientation
      b.outside = nb;
      b.old_cell = t;
      b.slot = i;
      boundary_.push_back(b);
    }
  }

  // One new cell per face of the region's boundary. Slots freed by this
  // insertion are reused only by the next, so that the outside cells' links
  // to the old cells stay unambiguous while they are rewritten.
  created_.clear();
  for (const Boundary& b : boundary_) {
    const uint32_t nc = newCellSlot();
    Cell& c = cells_[nc];
    for (int k = 0; k < 4; ++k) c.v[k] = b.v[k], c.n[k] = kNone;
    c.n[b.slot] = b.outside;
    Cell& o = cells_[b.outside];
    for (int k = 0; k < 4; ++k)
      if (o.n[k] == b.old_cell) o.n[k] = nc;
    created_.push_back(nc);
  }
  for (uint32_t t : conflict_) {
    if (isFinite(t)) --finite_cells_;
    cells_[t].v[0] = kNone;
  }

  // The new cells meet each other across faces through p: each such face is
  // p and an edge of the boundary, shared by exactly two new cells. Matched
  // by the edge in a small open-addressing table.
  size_t table = 64;
  while (table < 4 * boundary_.size()) table *= 2;
  if (edges_.size() < table) edges_.assign(table, EdgeEntry{0, 0, 0});
  const size_t mask = table - 1;
  size_t used_lo = SIZE_MAX, used_hi = 0;
  for (size_t bi = 0; bi < created_.size(); ++bi) {
    const uint32_t nc = created_[bi];
    const int s = boundary_[bi].slot;
    for (int j = 0; j < 4; ++j) {
      if (j == s) continue;
      uint32_t e0 = kNone, e1 = kNone;
      for (int k = 0; k < 4; ++k)
        if (k != s && k != j) (e0 == kNone ? e0 : e1) = cells_[nc].v[k];
      const uint64_t key = (uint64_t{std::min(e0, e1)} << 32) | std::max(e0, e1);
      size_t h = static_cast<size_t>((key * 0x9e3779b97f4a7c15ull) >> 40) & mask;
      for (;; h = (h + 1) & mask) {
        EdgeEntry& en = edges_[h];
        if (en.key == 0) {
          en = EdgeEntry{key, nc, j};
          used_lo = std::min(used_lo, h), used_hi = std::max(used_hi, h);
          break;
        }
        if (en.key == key && en.cell != kNone) {
          cells_[nc].n[j] = en.cell;
          cells_[en.cell].n[en.face] = nc;
          en.cell = kNone;  // matched; the key stays so probes pass it
          break;
        }
      }
    }
  }
  if (used_lo <= used_hi)
    std::fill(edges_.begin() + static_cast<std::ptrdiff_t>(used_lo),
              edges_.begin() + static_cast<std::ptrdiff_t>(used_hi) + 1, EdgeEntry{0, 0, 0});

  for (uint32_t nc : created_) {
    if (isFinite(nc)) ++finite_cells_;
    for (uint32_t v : cells_[nc].v) vertex_cell_[v] = nc;
  }
  for (uint32_t t : conflict_) free_.push_back(t);
  last_cell_ = created_.front();
  return pv;
}

}  // namespace mrsv::reconstruct
