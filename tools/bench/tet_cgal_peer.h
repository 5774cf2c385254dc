// The peer the PT benchmark measures against (issue 21): a tet mesh coarsened
// to a given tet count by CGAL's Tetrahedral_remeshing, its scalar fields
// resampled at the new vertices from the original mesh.
#pragma once

#include <cstddef>
#include <string>

#include "mrsv/tet_mesh.h"

namespace mrsv::bench {

struct CgalPeerOptions {
  // The count is reached when it is within this fraction of the target.
  double tolerance = 0.05;
  // Remeshing runs at most (each from the original mesh), the target edge
  // length corrected between them.
  int max_runs = 8;
  // CGAL's number_of_iterations per run (its default is 1; its examples use
  // 3). More iterations give better shaped tets and a steadier count.
  unsigned iterations = 3;
  // Boundary edges whose two faces' normals differ by more than this many
  // degrees are constrained (CGAL then keeps them on their polyline and
  // never flips them) and vertices on three or more of them never move: the
  // box of a CT crop keeps its edges and corners. The boundary itself is
  // remeshed (it must be, for the coarse levels: a 32^3 crop has 11,532
  // boundary faces, more than 5 % of its 178,746 tets) with its vertices
  // projected back onto the input's boundary surface.
  double feature_angle = 60.0;
};

struct CgalPeerResult {
  TetMesh mesh;  // positively oriented tets, every field of the input
  size_t target_tets = 0;
  double edge_length = 0.0;  // CGAL's target edge length of the run kept
  int runs = 0;
  double seconds = 0.0;      // the run kept: CGAL's remeshing alone
  double seconds_all = 0.0;  // every run, triangulation builds included
  size_t constrained_edges = 0;
  bool within_tolerance = false;  // else the closest run is kept
};

// `in` must be a valid tet mesh (checkTetMesh, positively oriented tets, a
// manifold complex). False with one line in `error` when CGAL cannot build a
// triangulation from it.
bool cgalCoarsen(const TetMesh& in, size_t target_tets, const CgalPeerOptions& options,
                 CgalPeerResult* result, std::string* error);

}  // namespace mrsv::bench
