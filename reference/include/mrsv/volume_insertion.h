// Delaunay vertex insertion for 3-D grids (spec 10; paper section 5.2): a
// tetrahedral mesh of a volume, refined greedily where the mesh is farthest
// from the samples, band by band when the stream arrives in parts.
//
// The mesh is always the Delaunay tetrahedralization of its vertex set under
// the symbolic perturbation of spec 10.2, so it depends on the set alone; the
// set depends only on the integer samples, the options and the stages. Every
// decision is exact integer arithmetic.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "mrsv/grid_mesh.h"
#include "mrsv/terrain_insertion.h"  // InsertionLimits, InsertionProgress

namespace mrsv {

// Which samples a stage inserts (spec 10.6).
enum class VolumeDistance {
  // Greedy: always the sample farthest from the mesh (the default, D62).
  kMesh,
  // The paper's 5.2 first: every new sample of the stage farther than
  // max_error from the trilinear interpolant of the corners of its cell of
  // the previous lattice, in sample order; then greedy as kMesh.
  kTrilinear,
};

class VolumeInserter {
 public:
  // A mesh of a size_x x size_y x size_z grid holding its eight corners.
  // Sides from 2 to 32768 (spec 10.1); others make refine() fail.
  VolumeInserter(uint32_t size_x, uint32_t size_y, uint32_t size_z);
  ~VolumeInserter();
  VolumeInserter(const VolumeInserter&) = delete;
  VolumeInserter& operator=(const VolumeInserter&) = delete;

  void setDistance(VolumeDistance distance);

  // One stage (spec 10.7): `field` holds the samples of the whole grid (as a
  // prefix of the stream decodes them); the candidates are the lattice
  // points whose coordinates are multiples of 2^shift, and the last index on
  // each axis. Vertices already in the mesh take the field's values; then
  // vertices are inserted, largest error first, until `limits` hold (its
  // border_rule is for terrains and is ignored). Stages only add. Returns
  // false with one line in `error` when the field does not fit or the
  // limits are unset.
  bool refine(const SampleField& field, unsigned shift, const InsertionLimits& limits,
              std::string* error, const InsertionProgress& progress = nullptr);

  // The largest error of a lattice sample of the last stage, num / den
  // (reduced; 0 / 1 when every sample is on the mesh).
  void maxError(int64_t* num, int64_t* den) const;
  uint64_t vertexCount() const;
  uint64_t cellCount() const;
  // Points in insertion order (the eight corners first), positive tets.
  void mesh(GridMesh* out) const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mrsv
