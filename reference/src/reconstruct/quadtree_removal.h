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

// Which vertices a removal pass tries, and how often.
struct RemovalRules {
  uint32_t max_passes;  // > 0: stop after that many passes; 0: until one removes none
  uint32_t max_link;    // a vertex whose link polygon has more points stays (at most 64)
  bool bent_stay;       // a vertex bent by more than E along both grid axes stays
};
// spec 9.7: the quadtree's pass, one pass over the stars of at most 6 link
// points, bent grid points staying (D86, D88): the stars a few removals have
// grown, and the peaks and pits, cost most and give least.
constexpr RemovalRules kAfterQuadtree{1, 6, true};
// spec 8.8: insertion's pass, pass after pass, links of up to 64 points.
constexpr RemovalRules kAfterInsertion{0, 64, false};

// Removes vertices of `mesh` (a 2-D grid mesh covering the whole grid, every
// triangle counter-clockwise) by the rules of spec 9.7 (and 8.8); the grid's
// border vertices stay. `test` is the max-error test the mesh was made with.
void removeVertices(const ErrorTest& test, GridMesh* mesh, const RemovalRules& rules, RemovalReport* report);

}  // namespace mrsv::quadtree
