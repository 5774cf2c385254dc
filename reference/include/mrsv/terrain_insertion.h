// Delaunay vertex insertion for 2-D grids (spec 8.4 to 8.7; paper section 5):
// a triangulated irregular network (TIN) of a terrain, refined greedily where
// the mesh is farthest from the samples, band by band when the stream arrives
// in parts.
//
// The mesh is always the Delaunay triangulation of its vertex set under the
// symbolic perturbation of spec 8.3, so it depends on the set alone; the set
// depends only on the integer samples, the options and the stages. Every
// decision is exact integer arithmetic.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "mrsv/grid_mesh.h"

namespace mrsv {

struct InsertionLimits {
  // Stop once every sample of the stage's lattice is within this of the mesh.
  ErrorBound max_error;
  // Stop once the mesh has at least this many triangles (0: no limit).
  uint64_t max_cells = 0;
  // The border rule (spec 8.6): each side of the grid is first refined by
  // 1-D insertion (paper 5.1) reading only that side's samples, to max_error,
  // so that two grids sharing a side get the same vertices there. Needs
  // max_error.
  bool border_rule = true;
};

// Called now and then with the cells made so far; return false to stop early
// (the mesh stays valid).
using InsertionProgress = std::function<bool(uint64_t cells)>;

class TerrainInserter {
 public:
  // A mesh of a size_x x size_y grid (both at least 2) holding its four corners.
  TerrainInserter(uint32_t size_x, uint32_t size_y);
  ~TerrainInserter();
  TerrainInserter(const TerrainInserter&) = delete;
  TerrainInserter& operator=(const TerrainInserter&) = delete;

  // One stage (spec 8.7): `field` holds the samples of the whole grid (as a
  // prefix of the stream decodes them); the candidates are the lattice points
  // whose coordinates are multiples of 2^shift, and the last row and column.
  // Vertices already in the mesh take the field's values; then vertices are
  // inserted, largest error first, until `limits` hold, the error bound
  // taken 2^(shift+1) times when shift > 0 (a coarse lattice stops sooner).
  // Stages only add.
  // Returns false with one line in `error` when the field does not fit or
  // the limits are unset.
  bool refine(const SampleField& field, unsigned shift, const InsertionLimits& limits,
              std::string* error, const InsertionProgress& progress = nullptr);

  // The largest error of a lattice sample of the last stage (informative;
  // decisions compare exactly), found by scanning every triangle again: the
  // field given to the last refine() must still exist.
  double maxError() const;
  uint64_t vertexCount() const;
  uint64_t cellCount() const;
  void mesh(GridMesh* out) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// spec 8.8, the border cleanup: one pass of the vertex-removal test (9.7)
// with bound E over the border zone of `mesh` (a 2-D mesh of `field`'s grid,
// as TerrainInserter::mesh() gives it): the inner vertices of the triangles
// that have a vertex on the grid's border. Every triangle it makes is within
// E, and the border's vertices stay, so tiles still meet. What the border
// rule's polylines cost in triangles is won back there (D88). Returns the
// vertices removed; false with `error` when the mesh is not a 2-D mesh of
// the field's size or E is not set.
// Whether spec 8.8's border cleanup follows an insertion with these limits:
// the border rule with a bound, and not progressive (a progressive run's
// vertex sets must each hold the previous one's). The caller also leaves it
// out when remove_vertices asks for 8.8's passes (they try every inner
// vertex) or the user turns it off.
inline bool borderCleanupApplies(const InsertionLimits& limits, bool progressive) {
  return limits.border_rule && limits.max_error.set() && !progressive;
}
bool cleanBorderZone(const SampleField& field, const ErrorBound& bound, GridMesh* mesh, uint64_t* removed,
                     std::string* error);

}  // namespace mrsv
