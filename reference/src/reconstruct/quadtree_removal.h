// spec 9.7: the vertex-removal pass after the max-error quadtree. Each
// interior vertex whose star can be re-triangulated with triangles within E
// leaves the mesh, finest first, in one pass (D86; after insertion, 8.8, pass
// after pass); the triangles then follow the terrain at any angle instead of
// the dyadic cells (D83).
#pragma once

#include <cstdint>

#include "mrsv/grid_mesh.h"
#include "reconstruct/quadtree_error.h"

namespace mrsv::quadtree {

struct RemovalReport {
  uint64_t removed = 0;  // vertices that left the mesh
  uint32_t passes = 0;   // passes made, the last one removing none
};

// Which inner vertices a pass tries: all of them (9.7, 8.8), or only those
// sharing an edge with a vertex on the grid's border (8.8, the border
// cleanup), taken from the mesh as it is on entry.
enum class RemovalCandidates { kAllInner, kBorderZone };

// Which vertices a removal pass tries, and how often.
struct RemovalRules {
  uint32_t max_passes;  // > 0: stop after that many passes; 0: until one removes none
  uint32_t max_link;    // a vertex whose link polygon has more points stays (at most 64)
  bool bent_stay;       // a vertex bent by more than E along both grid axes stays
  RemovalCandidates candidates = RemovalCandidates::kAllInner;
};
// spec 9.7: the quadtree's pass, one pass over the stars of at most 6 link
// points, bent grid points staying (D86, D89): the stars a few removals have
// grown, and the peaks and pits, cost most and give least.
constexpr RemovalRules kAfterQuadtree{1, 6, true};
// spec 8.8: insertion's pass, pass after pass, links of up to 64 points.
constexpr RemovalRules kAfterInsertion{0, 64, false};
// spec 8.8: insertion's border cleanup, one pass over the border zone.
constexpr RemovalRules kBorderCleanup{1, 64, false, RemovalCandidates::kBorderZone};

// Removes vertices of `mesh` (a 2-D grid mesh covering the whole grid, every
// triangle counter-clockwise) by the rules of spec 9.7 (and 8.8); the grid's
// border vertices stay. `test` is the max-error test the mesh was made with.
// The survivors keep their order in mesh->points.
void removeVertices(const ErrorTest& test, GridMesh* mesh, const RemovalRules& rules, RemovalReport* report);

}  // namespace mrsv::quadtree
