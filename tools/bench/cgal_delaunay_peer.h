// A peer for decoding a PT level (issue 21): CGAL's Delaunay_triangulation_3
// building a tet mesh of the same vertices, as the paper compares reaching a
// level of a progressive tetrahedralization with Delaunay insertion (7.2).
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace mrsv::bench {

// Seconds CGAL's Delaunay_triangulation_3 (exact predicates, inexact
// constructions) takes to triangulate `points` by its range insertion, which
// sorts them spatially first; its finite tets in *tets.
double cgalDelaunaySeconds(const std::vector<std::array<double, 3>>& points, size_t* tets);

}  // namespace mrsv::bench
