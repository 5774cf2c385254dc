// The tetrahedral complex a PT decoder (and the encoder that mirrors it) holds:
// integer positions and scalars, tets in slots, and each vertex's tets.
// spec: 7.3 (the mesh a decoder holds), 7.6 (links, vertex splits, edge collapses).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "tetmesh/exact_orient.h"
#include "tetmesh/incidence_lists.h"

namespace mrsv {

using Tet = std::array<uint32_t, 4>;

// The corner of t that is v (0 when none is). Without a branch: which
// corner a vertex is cannot be predicted, and gcc turns the plain sum of
// comparisons into one (cachegrind on the CT crop: 5 mispredictions per
// split in the link's build, 3 in the split).
inline int cornerOf(const Tet& t, uint32_t v) {
#if defined(__SSE2__)
  const __m128i corners = _mm_loadu_si128(reinterpret_cast<const __m128i*>(t.data()));
  const __m128i equal = _mm_cmpeq_epi32(corners, _mm_set1_epi32(static_cast<int>(v)));
  return __builtin_ctz(static_cast<unsigned>(_mm_movemask_ps(_mm_castsi128_ps(equal))) | 16u) & 3;
#else
  return (t[1] == v) + 2 * (t[2] == v) + 3 * (t[3] == v);
#endif
}

// spec 7.6.1: the link triangle of the corner at position i of a positive tet
// (a, b, c, d): the other three corners in the order that an even
// permutation moving corner i to the front leaves them.
constexpr int kLinkOrder[4][3] = {{1, 2, 3}, {0, 3, 2}, {0, 1, 3}, {0, 2, 1}};

// The link of a vertex v: for each tet (v, p, q, r) with v moved to the front
// by an even permutation, the oriented triangle (p, q, r). Local vertex i is
// the i-th smallest vertex number of the link; its corners list the triangles
// through it, rotated so that it comes first.
struct Link {
  uint32_t center = 0;
  std::vector<uint32_t> vertices;                  // ascending vertex numbers
  std::vector<std::array<uint32_t, 3>> triangles;  // local indices
  std::vector<uint32_t> triangle_tet;              // the tet slot of each triangle
  std::vector<uint32_t> corner_begin;              // CSR over local vertices
  std::vector<std::array<uint32_t, 3>> corners;    // (q, r, triangle) for local vertex p's triangle (p, q, r)
  std::vector<uint32_t> corner_next;               // the corner of p starting where corner k ends, or UINT32_MAX
  std::vector<uint32_t> corner_prev;               // the corner of p ending where corner k starts, or UINT32_MAX
  std::vector<std::array<uint32_t, 3>> triangle_corner;  // the corner of each triangle at its j-th vertex
  std::vector<uint8_t> on_boundary;                // per local vertex: an edge with one triangle
  bool has_boundary = false;

  uint32_t degree(uint32_t p) const { return corner_begin[p + 1] - corner_begin[p]; }
  // The triangle (p, q, ...) through p whose next corner is q, or -1.
  int64_t triangleFrom(uint32_t p, uint32_t q) const;
  // The triangle across the edge from triangle f's j-th vertex to its next
  // one (it holds that edge reversed), or -1 on the link's boundary.
  int64_t across(uint32_t f, int j) const {
    const uint32_t k = corner_prev[triangle_corner[f][j]];
    return k == UINT32_MAX ? -1 : static_cast<int64_t>(corners[k][2]);
  }
  // p's neighbours in rotation order (q -> r for each triangle (p, q, r))
  // starting at `start`, or at the start of the fan when p is on the
  // boundary. For an interior p that is the cycle of its deg neighbours;
  // for a boundary p the path of its deg + 1 neighbours. False when the
  // triangles around p do not form one fan (the link is not a manifold).
  bool rotation(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const;
  uint32_t localIndex(uint32_t vertex) const;  // vertices.size() when absent
  // The smallest link neighbour q of p with a triangle (p, q, ...).
  uint32_t lowestNeighbour(uint32_t p) const;
  // As StarLink's (which numbers its vertices otherwise), for the coding
  // templates: local numbers are ranks here.
  bool rotationFromLowest(uint32_t p, std::vector<uint32_t>* out) const {
    return rotation(p, lowestNeighbour(p), out);
  }
  uint32_t localOfRank(uint32_t r) const { return r; }
  uint32_t rotationInto(uint32_t p, uint32_t start, std::vector<uint32_t>* out) const {
    return rotation(p, start, out) ? static_cast<uint32_t>(out->size()) : 0;
  }
  uint32_t rotationFromLowestInto(uint32_t p, std::vector<uint32_t>* out) const {
    return rotationFromLowest(p, out) ? static_cast<uint32_t>(out->size()) : 0;
  }
  void boundaryVertices(std::vector<uint32_t>* out) const {
    out->clear();
    for (uint32_t p = 0; p < vertices.size(); ++p)
      if (on_boundary[p]) out->push_back(p);
  }

  // Scratch of buildLink(): per vertex number, its local index while its
  // stamp is the current one (no sort or search per corner).
  std::vector<uint32_t> local_of, stamp_of;
  uint32_t stamp = 0;
  std::vector<uint32_t> corner_of_q;  // per local vertex: the corner of the vertex at hand starting there
};

class TetComplex {
 public:
  int field_count = 0;
  // Large-page arrays: a PT decoder reserves them whole from THDR (7.2).
  LargeVector<Point3i> positions;
  LargeVector<int32_t> scalars;  // field_count per vertex
  LargeVector<Tet> tets;
  IncidenceLists incident;  // the tet slots of each vertex
  // Every coordinate is in [0, 2^position_bits): set by a PT decoder, which
  // checks each decoded coordinate against it. At 20 or less orientation()
  // skips orient3d's per-call test of the 64-bit bound (issue 21's profile:
  // ~19 tests per split).
  int position_bits = 30;

  uint32_t vertexCount() const { return static_cast<uint32_t>(positions.size()); }
  int orientation(const Tet& t) const {
    const Point3i &a = positions[t[0]], &b = positions[t[1]], &c = positions[t[2]], &d = positions[t[3]];
    return position_bits <= 20 ? orient3dBelow2to20(a, b, c, d) : orient3d(a, b, c, d);
  }
  // Builds `incident` from `tets` for the first `vertex_count` vertices.
  void buildIncidence();
  // The link of v (spec 7.6.1); reuses `link`'s storage.
  void buildLink(uint32_t v, Link* link) const;
  // Checks that every tet is positive with distinct corners and that every
  // vertex's link is a sphere or a disk (spec 7.4). Returns "" or the problem.
  std::string checkManifold() const;
};

// Whether a link is a triangulated sphere or disk: each directed edge once,
// one fan per vertex, connected, Euler characteristic 2 (no boundary) or 1.
std::string checkLinkIsSphereOrDisk(const Link& link);

}  // namespace mrsv
