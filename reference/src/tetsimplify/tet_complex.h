// The mutable tet complex the simplifier collapses: flat arrays, vertex stars
// as lists of tet corners in one pool (IncidenceLists, no allocation per
// collapse), and per tet a mask of which of its faces lie on the boundary.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "tetmesh/incidence_lists.h"
#include "tetsimplify/exact_predicates.h"

namespace mrsv::tetsimplify {

constexpr uint32_t kNone = 0xffffffffu;

class TetComplex {
 public:
  // Builds stars and boundary faces, checking the input: indices in range,
  // every tet positively oriented, every face in one tet or in two with
  // opposite orientations, every vertex link a sphere or a disk. On failure
  // `error` names the element and the rule.
  bool build(const std::vector<IPoint>& positions, const std::vector<std::array<uint32_t, 4>>& tets,
             std::string* error);

  uint32_t numVertices() const { return stars_.vertexCount(); }
  uint32_t numTetSlots() const { return static_cast<uint32_t>(tets_.size()); }
  uint64_t liveTets() const { return live_tets_; }
  uint64_t liveVertices() const { return live_vertices_; }
  // A vertex is alive while its list holds a corner (a walk drops dead ones).
  bool vertexAlive(uint32_t v) const { return !stars_.empty(v); }
  bool tetAlive(uint32_t t) const { return alive_[t] != 0; }
  bool onBoundary(uint32_t v) const { return boundary_vertex_[v] != 0; }
  const std::array<uint32_t, 4>& tet(uint32_t t) const { return tets_[t]; }
  // Bit f: the face opposite corner f is on the boundary.
  uint8_t boundaryMask(uint32_t t) const { return boundary_[t]; }
  const IPoint& position(uint32_t v) const { return positions_[v]; }
  const std::vector<IPoint>& positions() const { return positions_; }

  // Calls f(t, corner) for every live tet t of v's star, where
  // tet(t)[corner] == v; drops dead tets from the list on the way. f must
  // not walk v's list again nor change any list (no caller does).
  template <typename F>
  void forEachTet(uint32_t v, F&& f) {
    // A list is contiguous, so the tets a few entries ahead are loaded while
    // f works: as a linked list each step waited for the load of the next
    // corner (issue 21's profile of the LOX post: the simplifier's largest
    // stall).
    uint32_t* corners = stars_.data(v);
    const uint32_t n = stars_.size(v);
    uint32_t kept = 0;
    for (uint32_t i = 0; i < n; ++i) {
      if (i + 4 < n) __builtin_prefetch(&tets_[corners[i + 4] >> 2]);
      const uint32_t c = corners[i];
      if (!alive_[c >> 2]) continue;
      corners[kept++] = c;
      f(c >> 2, c & 3);
    }
    stars_.resize(v, kept);
  }

  // Collapses vt into vs (the caller has checked that it is valid): the tets
  // of both vanish, vt becomes vs in the others, faces whose tet vanished
  // pass their boundary status to the face they are glued to. Appends the
  // vanished tets to `vanished` if given.
  void collapse(uint32_t vs, uint32_t vt, std::vector<uint32_t>* vanished = nullptr);

 private:
  std::vector<IPoint> positions_;
  std::vector<std::array<uint32_t, 4>> tets_;
  std::vector<uint8_t> alive_;
  std::vector<uint8_t> boundary_;
  std::vector<uint8_t> boundary_vertex_;
  IncidenceLists stars_;  // per vertex, its corners (4 t + i) in star order; empty when dead
  std::vector<uint32_t> ring_;  // scratch for collapse()
  uint64_t live_tets_ = 0;
  uint64_t live_vertices_ = 0;
};

}  // namespace mrsv::tetsimplify
