// Adaptive meshes of grids: what the mesh reconstructors (spec 8) make from a
// decoded grid. Every decision a reconstructor takes reads only the integer
// samples of a SampleField and uses exact integer arithmetic, so that the
// canonical output below is the same in every conforming implementation.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/mesh.h"
#include "mrsv/tet_mesh.h"

namespace mrsv {

// A grid's samples as the reconstructors read them (spec 8.1): integers, x
// fastest, then y, then z. 2-D grids have size[2] == 1.
struct SampleField {
  uint32_t size[3] = {0, 0, 0};
  std::vector<int32_t> values;

  int dims() const { return size[2] > 1 ? 3 : 2; }
  uint64_t index(uint32_t x, uint32_t y, uint32_t z = 0) const {
    return (uint64_t{z} * size[1] + y) * size[0] + x;
  }
  int32_t at(uint32_t x, uint32_t y, uint32_t z = 0) const { return values[index(x, y, z)]; }
};

// The samples of a decoded grid of integer sample type (uint8, int16, uint16,
// int32). A no-data sample takes the value the wavelet synthesis gave it
// (spec 8.1); decode with DecodeOptions::void_values to have them. On failure
// returns false with one line in `error` (float samples, no samples, 1-D).
bool sampleFieldFromGrid(const DecodedGrid& grid, SampleField* field, std::string* error);

// A maximum error in sample units as an exact rational num / den (spec 8.3):
// a sample s is within it of a mesh value m when |s - m| <= num / den. Parsed
// from a decimal ("20", "2.5", "0.125") so that every implementation compares
// the same number; set() is false until parsed.
struct ErrorBound {
  int64_t num = -1;
  int64_t den = 1;
  bool set() const { return num >= 0; }
};
// Accepts 0 to 2^31 with at most 9 decimals; returns false otherwise.
bool parseErrorBound(const std::string& text, ErrorBound* bound);

// spec 8.7: the stages in which a stream's bytes refine a mesh, coarse to
// fine. Stage k reads the first `bytes` bytes (a prefix ending with the last
// band of a level; the last stage: all of `size`) and its lattice has step
// 2^shift. A stored grid, or a wavelet grid whose bytes hold no complete
// band, has one stage. `levels` > 0 drops the stages with shift < levels (the
// last stage left then ends at its band's chunk); the result may be empty.
// `grid` is the one-shot decode of all the bytes (decodeGrid with `size`).
struct ReconstructionStage {
  uint64_t bytes = 0;
  unsigned shift = 0;
};
std::vector<ReconstructionStage> reconstructionStages(const DecodedGrid& grid, uint64_t size, unsigned levels = 0);

// An adaptive mesh whose vertices are grid points. 2-D: triangles, counter-
// clockwise seen from +z (x right, y up), cell[3] unused; 3-D: tets, positively
// oriented (det[b - a, c - a, d - a] > 0).
struct GridMesh {
  int dims = 2;
  uint32_t size[3] = {0, 0, 0};               // the grid's sizes
  std::vector<std::array<uint32_t, 3>> points;  // grid coordinates (x, y, z); z = 0 in 2-D
  std::vector<int32_t> values;                 // the sample at each point
  std::vector<std::array<uint32_t, 4>> cells;  // indices into points
};

// spec 8.2: the canonical output, the bytes whose SHA-256 the conformance
// suite compares. Independent of the order of points and cells in `mesh`.
std::vector<uint8_t> canonicalGridMeshOutput(const GridMesh& mesh);

// Geometry for the file writers: position = origin + coordinate * spacing per
// axis; 2-D heights are the sample value times z_scale.
struct GridMeshGeometry {
  double origin[3] = {0, 0, 0};
  double spacing[3] = {1, 1, 1};
  double z_scale = 1;
};

// Reads `spacing` and `origin` from a stream's meta chunk (spec 2.6: numbers
// separated by commas, one per axis). Missing entries keep the defaults.
bool gridMeshGeometryFromMetadata(const Metadata& metadata, int dims, GridMeshGeometry* geometry,
                                  std::string* error);

// 2-D meshes as triangle meshes (the sample as the scalar), 3-D meshes as tet
// meshes (the sample as the field "value").
TriangleMesh gridMeshToTriangles(const GridMesh& mesh, const GridMeshGeometry& geometry);
TetMesh gridMeshToTets(const GridMesh& mesh, const GridMeshGeometry& geometry);

}  // namespace mrsv
