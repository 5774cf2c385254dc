// Quadtree vertex removal (spec 9, paper section 4): an adaptive triangle mesh
// of a 2-D grid made of the dyadic cells of a restricted quadtree, each cell
// triangulated by a look-up table on which of its edge midpoints its
// neighbours need. Every decision reads integer samples (or integer detail
// signals) and compares exactly, so the mesh is the same bit for bit in every
// conforming implementation (its canonical output, spec 8.2).
//
// Three ways to choose the tree:
//   - max_error E (exact, sample units): every sample of the grid lies within
//     E of the mesh (the linear interpolant over its triangle); a leaf stays
//     when some triangulation of its polygon (the table's, another one, or a
//     fan from its centre, in a fixed order) is within E, and takes the first;
//   - epsilon (the paper's wavelet criterion): a dyadic vertex is removed when
//     the squares of the detail signal over it and its 4-neighbourhood sum to
//     at most epsilon, bottom-up with the resolution and m to m-2 criteria;
//     needs the detail signals of the stream (quadtreeDetailsFromStream);
//   - max_triangles N: the smallest threshold of the criterion found by a
//     fixed bisection whose mesh has at most N triangles (spec 9.6).
// tile_borders (max-error only) makes each side of the grid a function of that
// side's samples alone, so that adjacent tiles meshed apart share every border
// vertex (spec 9.5).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "mrsv/grid.h"
#include "mrsv/grid_mesh.h"

namespace mrsv {

// The detail signal of each level m = 1..levels (spec 9.2): level m's values at
// the grid points whose coordinates are multiples of 2^(m-1), in the stream's
// fixed point (sample units times 2^frac_bits).
struct QuadtreeDetails {
  uint32_t size[2] = {0, 0};  // the grid's sizes
  int frac_bits = 0;
  // detail[m - 1][j * width(m) + i] is the value at grid point
  // (i * 2^(m-1), j * 2^(m-1)); width(m) = ((size[0] - 1) >> (m - 1)) + 1.
  std::vector<std::vector<int64_t>> detail;
  int levels() const { return static_cast<int>(detail.size()); }
  uint32_t width(int m) const { return ((size[0] - 1) >> (m - 1)) + 1; }
  uint32_t height(int m) const { return ((size[1] - 1) >> (m - 1)) + 1; }
};

// Decodes a 2-D wavelet-coded grid of integer samples (or a prefix with every
// band) once and gives its samples (`options` as for decodeGrid; void_values is
// forced on so that voids take their synthesised value, spec 8.1) and the
// detail signals of its levels. One line in `error` on failure.
bool quadtreeDetailsFromStream(const uint8_t* data, size_t size, const DecodeOptions& options,
                               SampleField* field, QuadtreeDetails* details, std::string* error);

enum class QuadtreeCriterion : uint8_t { kMaxError, kWavelet };

struct QuadtreeOptions {
  QuadtreeCriterion criterion = QuadtreeCriterion::kMaxError;
  // kMaxError: E in sample units. kWavelet: epsilon in sample units squared.
  // Ignored when max_triangles > 0.
  ErrorBound threshold;
  uint64_t max_triangles = 0;  // > 0: search the threshold (spec 9.6)
  bool tile_borders = false;   // spec 9.5; kMaxError only, grids of at least 4 x 4
  // spec 9.7 (kMaxError only): interior vertices removed after the tree, in one
  // pass over the links of at most 6 points, bent grid points staying, while
  // every triangle stays within E; 0.90 to 1.21 x insertion's triangles for
  // 1.9 to 2.8 x the tree's time (D83, D86, D89).
  bool remove_vertices = false;
};

// What the search of max_triangles settled on (null-safe to ignore).
struct QuadtreeReport {
  ErrorBound threshold;  // the threshold the mesh was made with
  uint32_t rounds = 0;   // refinement rounds of the max-error tree (spec 9.4)
  uint64_t vertices_removed = 0;  // by the vertex-removal pass (spec 9.7)
  uint32_t removal_passes = 0;
};

// Meshes a 2-D field (at least 2 x 2 samples). `details` is required by the
// wavelet criterion and ignored otherwise (may be null). On failure returns
// false with one line in `error` and leaves `out` empty.
bool quadtreeMesh(const SampleField& field, const QuadtreeDetails* details,
                  const QuadtreeOptions& options, GridMesh* out, std::string* error,
                  QuadtreeReport* report = nullptr);

// The vertex-removal pass of spec 9.7 on any 2-D mesh of `field` whose
// counter-clockwise triangles tile the grid's rectangle, each edge in two
// triangles or on the border (a mesh the reconstructors make; other meshes
// are not checked), with bound E (spec 8.8: after Delaunay insertion). Returns the vertices removed; false with `error` when
// the mesh is not a 2-D mesh of the field's size or E is not set.
bool removeInnerVertices(const SampleField& field, const ErrorBound& bound, GridMesh* mesh,
                         uint64_t* removed, std::string* error);

}  // namespace mrsv
