// The link condition (link_condition.h). Every simplex of Lk(a) n Lk(b) is
// made of common neighbours of a and b, and the vertex condition (checked
// first) puts all of those on the ring of ab (the vertices of Lk(ab)), so
// edges and triangles are compared as small bit sets over the ring's indices.
// The dummy vertex w contributes: w itself (a and b both on the boundary:
// then ab must be a boundary edge), edges w p (a p and b p boundary edges:
// then a b p must be a boundary face) and triangles w p q (a p q and b p q
// both boundary faces: never allowed, Lk(ab) has no triangles).
#include "tetsimplify/link_condition.h"

namespace mrsv::tetsimplify {

namespace {

inline void setPair(uint64_t* m, int i, int j) {
  m[i] |= uint64_t(1) << j;
  m[j] |= uint64_t(1) << i;
}

inline uint32_t packTriangle(int i, int j, int k) {
  if (i > j) std::swap(i, j);
  if (j > k) std::swap(j, k);
  if (i > j) std::swap(i, j);
  return uint32_t(i) << 16 | uint32_t(j) << 8 | uint32_t(k);
}

}  // namespace

int LinkCondition::addToRing(uint32_t v) {
  if (ring_stamp_[v] == stamp_) return ring_index_[v];
  if (ring_size_ == 64) {
    overflow_ = true;
    return 0;
  }
  const int i = ring_size_++;
  ring_stamp_[v] = stamp_;
  ring_index_[v] = uint8_t(i);
  ring_edge_[i] = edge_a_[i] = edge_b_[i] = face_a_[i] = face_b_[i] = 0;
  return i;
}

bool LinkCondition::holds(TetComplex& complex, uint32_t a, uint32_t b, bool split_rule) {
  if (++stamp_ == 0) {  // wrapped: clear the stamps once every 2^32 checks
    std::fill(in_link_a_.begin(), in_link_a_.end(), 0);
    std::fill(ring_stamp_.begin(), ring_stamp_.end(), 0);
    stamp_ = 1;
  }
  ring_size_ = 0;
  overflow_ = false;
  boundary_edge_a_ = boundary_edge_b_ = boundary_face_ab_ = 0;
  triangles_a_.clear();
  bool ab_on_boundary = false;

  // Pass 1: Lk(a)'s vertices, and the ring tets a b p q with their boundary faces.
  complex.forEachTet(a, [&](uint32_t t, uint32_t ca) {
    const auto& v = complex.tet(t);
    int cb = -1;
    for (int i = 0; i < 4; ++i) {
      if (i != int(ca)) in_link_a_[v[i]] = stamp_;
      if (v[i] == b) cb = i;
    }
    if (cb < 0) return;
    int cp = -1, cq = -1;
    for (int i = 0; i < 4; ++i) {
      if (i != int(ca) && i != cb) (cp < 0 ? cp : cq) = i;
    }
    const int p = addToRing(v[cp]), q = addToRing(v[cq]);
    setPair(ring_edge_, p, q);
    const uint8_t mask = complex.boundaryMask(t);
    if (mask >> cb & 1) {  // a p q
      setPair(face_a_, p, q);
      boundary_edge_a_ |= uint64_t(1) << p | uint64_t(1) << q;
    }
    if (mask >> ca & 1) {  // b p q
      setPair(face_b_, p, q);
      boundary_edge_b_ |= uint64_t(1) << p | uint64_t(1) << q;
    }
    if (mask >> cq & 1) {  // a b p
      ab_on_boundary = true;
      boundary_face_ab_ |= uint64_t(1) << p;
      boundary_edge_a_ |= uint64_t(1) << p;
      boundary_edge_b_ |= uint64_t(1) << p;
    }
    if (mask >> cp & 1) {  // a b q
      ab_on_boundary = true;
      boundary_face_ab_ |= uint64_t(1) << q;
      boundary_edge_a_ |= uint64_t(1) << q;
      boundary_edge_b_ |= uint64_t(1) << q;
    }
  });
  if (overflow_ || ring_size_ == 0) return false;
  // w in Lk(a) n Lk(b) needs the triangle w a b: ab on the boundary.
  if (complex.onBoundary(a) && complex.onBoundary(b) && !ab_on_boundary) return false;

  // Pass 2: Lk(a)'s edges, triangles and boundary faces off the ring tets.
  complex.forEachTet(a, [&](uint32_t t, uint32_t ca) {
    const auto& v = complex.tet(t);
    int r[3], n = 0;
    uint32_t corners[3];
    for (uint32_t i = 0; i < 4; ++i) {
      if (i == ca) continue;
      if (v[i] == b) return;
      corners[n] = i;
      r[n++] = ringIndex(v[i]);
    }
    const uint8_t mask = complex.boundaryMask(t);
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      if (r[j] >= 0 && r[k] >= 0) setPair(edge_a_, r[j], r[k]);
      if (mask >> corners[i] & 1) {  // face a, v[corners[j]], v[corners[k]]
        if (r[j] >= 0) boundary_edge_a_ |= uint64_t(1) << r[j];
        if (r[k] >= 0) boundary_edge_a_ |= uint64_t(1) << r[k];
        if (r[j] >= 0 && r[k] >= 0) setPair(face_a_, r[j], r[k]);
      }
    }
    if (r[0] >= 0 && r[1] >= 0 && r[2] >= 0) triangles_a_.push_back(packTriangle(r[0], r[1], r[2]));
  });

  // Pass 3: Lk(b) off the ring tets, against Lk(a).
  bool ok = true;
  complex.forEachTet(b, [&](uint32_t t, uint32_t cb) {
    if (!ok) return;
    const auto& v = complex.tet(t);
    int r[3], n = 0;
    uint32_t corners[3];
    for (uint32_t i = 0; i < 4; ++i) {
      if (i == cb) continue;
      if (v[i] == a) return;
      corners[n] = i;
      r[n] = ringIndex(v[i]);
      // A common neighbour off the ring: vertex condition broken.
      if (r[n] < 0 && in_link_a_[v[i]] == stamp_) ok = false;
      ++n;
    }
    const uint8_t mask = complex.boundaryMask(t);
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      if (r[j] >= 0 && r[k] >= 0) setPair(edge_b_, r[j], r[k]);
      if (mask >> corners[i] & 1) {
        if (r[j] >= 0) boundary_edge_b_ |= uint64_t(1) << r[j];
        if (r[k] >= 0) boundary_edge_b_ |= uint64_t(1) << r[k];
        if (r[j] >= 0 && r[k] >= 0) setPair(face_b_, r[j], r[k]);
      }
    }
    if (r[0] >= 0 && r[1] >= 0 && r[2] >= 0) {
      const uint32_t key = packTriangle(r[0], r[1], r[2]);
      for (uint32_t k : triangles_a_) {
        if (k == key) ok = false;
      }
    }
  });
  if (!ok) return false;
  for (int i = 0; i < ring_size_; ++i) {
    if ((edge_a_[i] & edge_b_[i] & ~ring_edge_[i]) != 0) return false;  // edge p q
    if ((face_a_[i] & face_b_[i]) != 0) return false;                    // triangle w p q
    // The PT decoder's split rule, stricter than the link condition: after
    // the collapse the ring of ab is a path in a's link disk whose inner
    // edges (the faces a p q the ring tets leave) are inside the disk, so no
    // ring tet may have a boundary face a p q or b p q ...
    if (split_rule && ((face_a_[i] | face_b_[i]) & ring_edge_[i]) != 0) return false;
  }
  if ((boundary_edge_a_ & boundary_edge_b_ & ~boundary_face_ab_) != 0) return false;  // edge w p
  // ... and whose inner vertices are inside it: no boundary edge a p or b p
  // to a ring vertex but the path's two ends (the p with a b p on the boundary).
  return !split_rule || ((boundary_edge_a_ | boundary_edge_b_) & ~boundary_face_ab_) == 0;
}

}  // namespace mrsv::tetsimplify
