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
// sharing an edge with a vertex on the grid's border (8.9, the border cleanup).
enum class RemovalCandidates { kAllInner, kBorderZone };

// Removes vertices of `mesh` (a 2-D grid mesh covering the whole grid, every
// triangle counter-clockwise) by the rules of spec 9.7; the grid's border
// vertices stay. `test` is the max-error test the mesh was made with.
// max_passes > 0 stops after that many passes; 0 goes on until a pass removes
// none. kBorderZone takes the candidates from `mesh` as it is on entry.
void removeVertices(const ErrorTest& test, GridMesh* mesh, uint32_t max_passes, RemovalReport* report,
                    RemovalCandidates candidates = RemovalCandidates::kAllInner);

}  // namespace mrsv::quadtree
