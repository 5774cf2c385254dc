// A vertex split as the PT decoder applies it, against the StarLink it
// decoded the cut in: the region (7.6.3), the checks and changes (7.6.4).
// spec: 7.6.3, 7.6.4.
//
// The result is splitRegion() then applySplit() (vertex_split.h) to the
// slot: the same moved tets in the same order, the same tets and incidence
// lists, the same rule reported on failure. What the link already holds is
// not recomputed (issue 21's profile: region and split were a third of a
// decoded split):
// - every tet the split changes or adds has vt as a corner, so each link
//   vertex is subtracted from vt once and each orientation test is one
//   determinant of three such differences; a moved tet's link triangle
//   (p, q, r) gives orient3d(vt, p, q, r), which is the orientation of the
//   tet with vt in place of vs (an even permutation of its corners, 7.6.1);
// - vs's list is the link's triangle_tet in order, and the region marks its
//   moved tets: vs keeps the unmarked ones without reading the tets again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tetmesh/star_link.h"
#include "tetmesh/tet_complex.h"
#include "tetmesh/vertex_split.h"

namespace mrsv {

// Splits link->center (vs), the link built from `mesh` as it stands, by the
// cut `walk` (local vertices of `link`; `closed` for a cycle); vt is the
// complex's last vertex, with its position set and an empty tet list.
// On success `moved` holds the moved tets (splitRegion()'s order) and
// `walk_global` the cut as vertex numbers. Returns "" or the rule broken
// (nothing changed). The flood forgets the cut's edges in `link`
// (StarLink::forgetEdge), which is built again for the next split.
std::string applyStarSplit(TetComplex* mesh, StarLink* link, uint32_t vt, const std::vector<uint32_t>& walk,
                           bool closed, SplitScratch* scratch, std::vector<uint32_t>* moved,
                           std::vector<uint32_t>* walk_global);

}  // namespace mrsv
