// The mutable connectivity the simplifier collapses edges in: a half-edge
// structure over the input's triangle array, in flat arrays so that a collapse
// costs O(degree) and never allocates.
//
// Half-edge h = 3t + i runs from corner i of triangle t to corner (i+1) % 3;
// `vertexOf(h)` is its origin. A dead triangle has all three corners kNone.
// Every live vertex keeps one outgoing half-edge; on the boundary it is the
// outgoing boundary half-edge, the clockwise end of the vertex's fan, so that a
// counter-clockwise sweep from it visits the whole fan and boundary tests are
// O(1).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/mesh.h"

namespace mrsv::simplify {

inline constexpr uint32_t kNone = 0xffffffffu;

class EdgeTopology {
 public:
  // Builds the structure; false with one line in `error` unless the mesh is an
  // oriented 2-manifold with boundary (every directed edge used once, at most
  // two triangles per edge, one fan per vertex, no repeated corner).
  bool build(const TriangleMesh& mesh, std::string* error);

  static uint32_t next(uint32_t h) { return h % 3 == 2 ? h - 2 : h + 1; }
  static uint32_t prev(uint32_t h) { return h % 3 == 0 ? h + 2 : h - 1; }
  static uint32_t triangleOf(uint32_t h) { return h / 3; }

  uint32_t vertexOf(uint32_t h) const { return he_[h].corner; }
  uint32_t target(uint32_t h) const { return he_[next(h)].corner; }
  uint32_t opposite(uint32_t h) const { return he_[h].opposite; }
  uint32_t outgoing(uint32_t v) const { return outgoing_[v]; }
  bool alive(uint32_t v) const { return outgoing_[v] != kNone; }
  bool triangleAlive(uint32_t t) const { return he_[3 * t].corner != kNone; }
  // Whether live vertex v is on the boundary. Allowed collapses never change
  // it (collapse_checks.h), so it is kept per vertex from the start: a byte
  // read instead of two scattered ones in the hottest checks.
  bool onBoundary(uint32_t v) const { return boundary_[v] != 0; }
  bool edgeOnBoundary(uint32_t h) const { return he_[h].opposite == kNone; }

  // Counter-clockwise successor of the outgoing half-edge h around its origin,
  // kNone past the end of a boundary fan.
  uint32_t rotateCcw(uint32_t h) const { return he_[prev(h)].opposite; }

  uint32_t numVertices() const { return static_cast<uint32_t>(outgoing_.size()); }
  uint32_t numTriangles() const { return static_cast<uint32_t>(he_.size() / 3); }
  uint64_t liveTriangles() const { return live_triangles_; }

  // Calls f(h) for every outgoing half-edge of live vertex v, counter-clockwise
  // from the clockwise end of a boundary fan.
  template <typename F>
  void forEachOutgoing(uint32_t v, F&& f) const {
    const uint32_t start = outgoing_[v];
    uint32_t h = start;
    do {
      f(h);
      h = he_[prev(h)].opposite;
    } while (h != kNone && h != start);
  }

  // Calls f(w) for every neighbour w of live vertex v, counter-clockwise.
  template <typename F>
  void forEachNeighbour(uint32_t v, F&& f) const {
    const uint32_t start = outgoing_[v];
    uint32_t h = start;
    for (;;) {
      f(he_[next(h)].corner);
      const uint32_t p = prev(h);
      h = he_[p].opposite;
      if (h == start) return;
      if (h == kNone) {
        f(he_[p].corner);  // the far end of the incoming boundary half-edge
        return;
      }
    }
  }

  // The half-edge from a to b, or kNone when a and b are not adjacent
  // (a boundary edge has only one of its two directions).
  uint32_t findHalfEdge(uint32_t a, uint32_t b) const;

  // Merges `removed` into `kept`; h is either half-edge of their edge. The
  // caller has checked the link condition and the boundary rules
  // (collapse_checks.h); this only rewires. Triangles are never renumbered and
  // half-edge slots are never reused, so a stored half-edge index either still
  // means the same edge or belongs to a dead triangle.
  void collapse(uint32_t removed, uint32_t kept, uint32_t h);

  // Full consistency check, O(size): orientation, opposite pairing, fans,
  // boundary invariant. For tests and debug builds.
  bool validate(std::string* error) const;

  // The live triangles, with input vertex indices.
  void liveTriangleList(std::vector<std::array<uint32_t, 3>>* out) const;

 private:
  void settleOutgoing(uint32_t v, uint32_t any_outgoing);

  // Per half-edge (3 per triangle) its origin and its opposite, side by
  // side: walking a fan reads both, and one cache line instead of two per
  // triangle is most of the cost of a walk on a large mesh.
  struct HalfEdge {
    uint32_t corner;
    uint32_t opposite;
  };
  std::vector<HalfEdge> he_;
  std::vector<uint32_t> outgoing_;  // 1 per vertex, kNone if dead or unused
  std::vector<uint8_t> boundary_;   // 1 per vertex
  uint64_t live_triangles_ = 0;
};

}  // namespace mrsv::simplify
