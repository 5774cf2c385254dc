// The link condition for contracting an edge of a 3-manifold with boundary
// (Dey, Edelsbrunner, Guha, Nekhayev, "Topology preserving edge
// contraction"): Lk(a) n Lk(b) = Lk(ab), with links taken in the complex
// extended by a dummy vertex w coned over the boundary. It holds exactly when
// the contraction keeps the topology; checked here on vertices, edges and
// triangles of the links, all of which lie on the ring of the edge ab.
#pragma once

#include <cstdint>
#include <vector>

#include "tetsimplify/tet_complex.h"

namespace mrsv::tetsimplify {

class LinkCondition {
 public:
  void init(uint32_t num_vertices) {
    in_link_a_.assign(num_vertices, 0);
    ring_stamp_.assign(num_vertices, 0);
    ring_index_.assign(num_vertices, 0);
    stamp_ = 0;
  }
  // Whether edge (a, b) may be contracted. Rings of more than 64 vertices are
  // refused (never seen in practice; they would need wider bit sets). With
  // `split_rule`, also the PT decoder's rule for splitting a back into a and
  // b: the ring of ab is a cycle (a inside) or a path through the inside of
  // a's link disk with its two ends on the disk's rim (a on the boundary).
  // The link condition alone allows paths that touch the rim between their
  // ends (and the cycles of Table 1's cases 2 and 3).
  bool holds(TetComplex& complex, uint32_t a, uint32_t b, bool split_rule);

 private:
  int ringIndex(uint32_t v) const { return ring_stamp_[v] == stamp_ ? int(ring_index_[v]) : -1; }
  int addToRing(uint32_t v);

  std::vector<uint32_t> in_link_a_;
  std::vector<uint32_t> ring_stamp_;
  std::vector<uint8_t> ring_index_;
  uint32_t stamp_ = 0;
  int ring_size_ = 0;
  bool overflow_ = false;
  // Bit sets over pairs of ring vertices: edges of Lk(ab), edges of Lk(a) and
  // Lk(b) off the ring tets, and boundary faces a p q and b p q.
  uint64_t ring_edge_[64], edge_a_[64], edge_b_[64], face_a_[64], face_b_[64];
  // Per ring vertex p: a p, b p boundary edges, a b p a boundary face.
  uint64_t boundary_edge_a_ = 0, boundary_edge_b_ = 0, boundary_face_ab_ = 0;
  std::vector<uint32_t> triangles_a_;  // triples of ring indices, packed
};

}  // namespace mrsv::tetsimplify
