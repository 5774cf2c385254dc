// A guard against the largest deviations, which the memoryless quadrics do
// not see (spec 6.9, decision D32).
//
// A quadric measures how far the kept vertex lands from the planes of the
// fans as they are now. It misses two things that decide the Hausdorff
// distance: an input vertex that the collapse leaves far from the surface
// (the tip of a spike, whose triangles' planes all pass near the new
// position), and a new position that lands far from the input (a volume-
// preserving optimum at a thin tip overshoots). Each vertex therefore keeps a
// few of the input vertices it stands for ("members"), and a collapse about
// to be made is charged
//
//   weight * area * max(d_out^2, d_in^2),
//
// area the new fan's area, d_out the largest distance of a member of either
// end from the new fan, d_in the distance of the new position from the input
// triangles around those members (from below: see cost()). The simplifier orders collapses by the
// larger of this and the quadric cost, so the guard only reorders collapses
// whose deviation is far above what their quadric suggests.
//
// Members are capped at kMaxMembers per vertex, keeping those farthest from
// the vertex's fan: without the cap the last collapses would each look at
// most of the input, and the run would be quadratic.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "mrsv/mesh.h"
#include "simplify/edge_topology.h"
#include "simplify/vec3.h"

namespace mrsv::simplify {

class DeviationGuard {
 public:
  static constexpr uint32_t kMaxMembers = 16;

  // The input mesh, before any collapse (its positions stay the reference).
  void init(const TriangleMesh& mesh, double weight);

  // The guard's cost of collapsing `removed` into `kept` placed at x, with the
  // current topology and positions (before the collapse).
  double cost(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t removed,
              uint32_t kept, const Vec3& x) const;

  // Asks the member lists of a and b into the cache ahead of a cost() of
  // their edge: nothing nearby reads them, so each was a cache miss there.
  void prefetch(uint32_t a, uint32_t b) const {
    __builtin_prefetch(&members_[a]);
    __builtin_prefetch(&members_[b]);
  }

  // After the collapse (topology and positions updated): `kept` stands for the
  // members of both ends, the farthest kMaxMembers from its new fan.
  void merge(const EdgeTopology& topo, const std::vector<Vec3>& positions, uint32_t removed,
             uint32_t kept);

 private:
  struct Members {
    uint32_t count = 0;
    std::array<uint32_t, kMaxMembers> vertex{};
  };
  // An input vertex and its longest input edge: no point of its triangles is
  // further from it.
  struct InputVertex {
    Vec3 position;
    double reach;
  };
  std::vector<InputVertex> input_;
  std::vector<Members> members_;
  double weight_ = 0.0;
};

}  // namespace mrsv::simplify
